#version 460
// Last pass of the segment mask (paper section 4.3), in place in the R16F
// field: the smoothed indicator s becomes maskEncode(s, inside), with inside
// read from the indicator texture. (The distance field needs no last pass:
// its passes store DT in mm.) See shared/feature_bake.h.
#extension GL_GOOGLE_include_directive : require
#include "shared/feature_bake.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(set = 0, binding = CW_FEATURE_BIND_SOURCE) uniform sampler3D sourceTex;
layout(set = 0, binding = CW_FEATURE_BIND_OUT, r16f) uniform image3D field;
layout(push_constant) uniform Push {
    FeatureBakeParams params;
};

void main() {
    ivec3 p = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(p, params.dims))) return;
    float s = imageLoad(field, p).r;
    imageStore(field, p, vec4(maskEncode(s, texelFetch(sourceTex, p, 0).r > 0.5)));
}

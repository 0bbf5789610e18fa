#version 460
// Last pass of both feature bakes (paper sections 4.2, 4.3): the R16F texel
// of a scalar field held in an r32f image. mode 0: the field is the squared
// distance (mm^2), the texel DT in mm. mode 1: the field is the smoothed
// indicator s, the texel maskEncode(s, inside) with inside read from the
// indicator texture. See shared/feature_bake.h.
#extension GL_GOOGLE_include_directive : require
#include "shared/feature_bake.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(set = 0, binding = 0) uniform sampler3D sourceTex;
layout(set = 0, binding = 1, r32f) uniform readonly image3D srcImage;
layout(set = 0, binding = 3, r16f) uniform writeonly image3D outImage;
layout(push_constant) uniform Push { FeatureBakeParams params; };

void main() {
    ivec3 p = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(p, params.dims))) return;
    float f = imageLoad(srcImage, p).r;
    float value = params.mode == 0 ? distanceFromSquared(f)
                                   : maskEncode(f, texelFetch(sourceTex, p, 0).r > 0.5);
    imageStore(outImage, p, vec4(value));
}

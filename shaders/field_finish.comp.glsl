#version 460
// Last pass of both feature bakes (paper sections 4.2, 4.3): the RGBA16F
// texel of a scalar field held in an r32f image. mode 0: the field is the
// squared distance (mm^2), w = DT in mm. mode 1: the field is the smoothed
// indicator s, w = maskEncode(s, inside) with inside read from the indicator
// texture. xyz = unit gradient of w's field (DT or s) by central differences,
// neighbours clamped to the grid, per mm. See shared/feature_bake.h.
#extension GL_GOOGLE_include_directive : require
#include "shared/feature_bake.h"

// Each invocation walks kColumn voxels along z, keeping the field below, at
// and above the voxel: 5 loads per voxel instead of 7.
#define kColumn 16
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(set = 0, binding = 0) uniform sampler3D sourceTex;
layout(set = 0, binding = 1, r32f) uniform readonly image3D srcImage;
layout(set = 0, binding = 3, rgba16f) uniform writeonly image3D outImage;
layout(push_constant) uniform Push { FeatureBakeParams params; };

float fieldAt(ivec3 p) {
    float f = imageLoad(srcImage, clamp(p, ivec3(0), params.dims - 1)).r;
    return params.mode == 0 ? distanceFromSquared(f) : f;
}

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID.xy, gl_GlobalInvocationID.z * kColumn);
    if (any(greaterThanEqual(id, params.dims))) return;
    float below = fieldAt(id - ivec3(0, 0, 1));
    float here = fieldAt(id);
    for (int i = 0; i < kColumn && id.z + i < params.dims.z; ++i) {
        ivec3 p = id + ivec3(0, 0, i);
        float above = fieldAt(p + ivec3(0, 0, 1));
        vec3 delta = vec3(fieldAt(p + ivec3(1, 0, 0)) - fieldAt(p - ivec3(1, 0, 0)),
                          fieldAt(p + ivec3(0, 1, 0)) - fieldAt(p - ivec3(0, 1, 0)), above - below);
        float value = here;
        if (params.mode == 1) value = maskEncode(value, texelFetch(sourceTex, p, 0).r > 0.5);
        imageStore(outImage, p, vec4(unitOrZero(delta * params.halfInvSpacing), value));
        below = here;
        here = above;
    }
}

#version 460
// Segment alignment's feature texture over one operator's region: M copied
// from the baked segment mask, and the value moved material reads (movedValue
// in shared/feature_bake.h). One invocation per voxel of the region.
#extension GL_GOOGLE_include_directive : require
#include "shared/feature_bake.h"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(set = 0, binding = 0) uniform sampler3D volumeTex; // normalized values
layout(set = 0, binding = 1) uniform sampler3D maskTex;   // M over the volume's grid
layout(set = 0, binding = 2, rg16f) uniform writeonly image3D region;
layout(push_constant) uniform Push { FeatureRegionParams params; };

void main() {
    ivec3 j = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(j, params.size))) return;
    ivec3 v = params.lo + j;
    float m = texelFetch(maskTex, v, 0).r;
    float own = texelFetch(volumeTex, v, 0).r;
    bool inside = maskInside(m);
    float sum = 0.0, count = 0.0;
    // The loop runs only for the segment's voxels (a loop, not an if: lavapipe
    // leaves a loop when no lane takes it, but runs both sides of a branch).
    for (int dz = -1; dz <= (inside ? 1 : -2); ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                ivec3 n = v + ivec3(dx, dy, dz);
                if (any(lessThan(n, ivec3(0))) || any(greaterThanEqual(n, params.dims))) continue;
                if (maskInside(texelFetch(maskTex, n, 0).r)) continue; // itself included
                sum += texelFetch(volumeTex, n, 0).r;
                count += 1.0;
            }
    imageStore(region, j, vec4(m, movedValue(own, inside, sum, count), 0.0, 0.0));
}

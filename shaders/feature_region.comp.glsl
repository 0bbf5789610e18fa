#version 460
// Segment alignment's feature texture over one operator's region: M copied
// from the baked segment mask, and the value moved material reads (movedValue
// in shared/feature_bake.h). One invocation per voxel of the region; each
// workgroup first reads its block of voxels and their neighbours into shared
// memory once (2.3 fetches of each texture per voxel instead of up to 27).
#extension GL_GOOGLE_include_directive : require
#include "shared/feature_bake.h"

#define kGroup ivec3(8, 8, 4)
#define kTile (kGroup + 2)
#define kTileTexels (kTile.x * kTile.y * kTile.z)
layout(local_size_x = 8, local_size_y = 8, local_size_z = 4) in;
layout(set = 0, binding = CW_REGION_BIND_VALUES) uniform sampler3D volumeTex; // normalized values
layout(set = 0,
       binding = CW_REGION_BIND_MASK) uniform sampler3D maskTex; // M over the volume's grid
layout(set = 0, binding = CW_REGION_BIND_OUT, rg16f) uniform writeonly image3D region;
layout(push_constant) uniform Push {
    FeatureRegionParams params;
};

shared float tileMask[kTileTexels]; // 1 (inside: skipped) beyond the grid
shared float tileValue[kTileTexels];

int tileIndex(ivec3 t) {
    return t.x + kTile.x * (t.y + kTile.y * t.z);
}

void main() {
    ivec3 first = params.lo + ivec3(gl_WorkGroupID) * kGroup - 1; // the tile's voxel (0,0,0)
    int local = int(gl_LocalInvocationIndex);
    for (int i = local; i < kTileTexels; i += kGroup.x * kGroup.y * kGroup.z) {
        ivec3 t = ivec3(i % kTile.x, (i / kTile.x) % kTile.y, i / (kTile.x * kTile.y));
        ivec3 v = first + t;
        bool inGrid = all(greaterThanEqual(v, ivec3(0))) && all(lessThan(v, params.dims));
        ivec3 at = clamp(v, ivec3(0), params.dims - 1);
        tileMask[i] = inGrid ? texelFetch(maskTex, at, 0).r : 1.0;
        tileValue[i] = texelFetch(volumeTex, at, 0).r;
    }
    barrier();

    ivec3 j = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(j, params.size))) return;
    ivec3 centre = ivec3(gl_LocalInvocationID) + 1;
    float m = tileMask[tileIndex(centre)];
    float own = tileValue[tileIndex(centre)];
    bool inside = maskInside(m);
    float sum = 0.0, count = 0.0;
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                int n = tileIndex(centre + ivec3(dx, dy, dz));
                bool outside = !maskInside(tileMask[n]); // itself and beyond the grid: inside
                sum += outside ? tileValue[n] : 0.0;
                count += outside ? 1.0 : 0.0;
            }
    imageStore(region, j, vec4(m, movedValue(own, inside, sum, count), 0.0, 0.0));
}

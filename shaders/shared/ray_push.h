// The ray caster's push constants (shaders/glsl/ray_march.h), set per
// dispatch by render/raycast/raycaster.cpp.
#ifndef CUTAWAY_RAY_PUSH_H
#define CUTAWAY_RAY_PUSH_H

#include "shared/glsl_cpp.h"

CW_NAMESPACE_BEGIN

struct RayPush {
    mat4 clipToWorld;
    vec4 boxLo; // the occupied cells' bounds (world, mm)
    vec4 boxHi;
    vec4 cellsPerTexture; // xyz: cells across the texture, the last one partial;
                          // w: the longest slab they cover (voxels along each axis)
    uint bandStride;      // the order of the tiles' bands: shared/tile_order.h
    uint tileOffset;      // the dispatch's first tile: x | y << 16
    uint operatorTilesLo; // the tiles the rays of the operators' boxes cross,
    uint operatorTilesHi; // [lo, hi) (x | y << 16), which the shader with
                          // operators renders and the one without leaves
};

CW_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(cutaway::shader::RayPush) == 128,
              "Vulkan guarantees 128 bytes of push constants");
static_assert(offsetof(cutaway::shader::RayPush, boxLo) == 64);
static_assert(offsetof(cutaway::shader::RayPush, boxHi) == 80);
static_assert(offsetof(cutaway::shader::RayPush, cellsPerTexture) == 96);
static_assert(offsetof(cutaway::shader::RayPush, bandStride) == 112);
static_assert(offsetof(cutaway::shader::RayPush, tileOffset) == 116);
static_assert(offsetof(cutaway::shader::RayPush, operatorTilesLo) == 120);
static_assert(offsetof(cutaway::shader::RayPush, operatorTilesHi) == 124);
#endif

#endif

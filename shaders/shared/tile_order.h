// The order in which the ray caster's workgroups take the image's 8x8-pixel tiles, and its
// invocations a tile's pixels. lavapipe (Mesa 22.3, lp_cs_tpool) gives each of its N threads one
// contiguous Nth of a dispatch's workgroups (x fastest), which it marches in order: in image
// order one core would march the top half of the picture and the other the bottom half, and a
// head whose skull fills one half keeps one core idle while the other finishes. So the tile rows
// go in bands of kTileBand, and workgroup band g takes tile band (g * stride) mod bands, with a
// stride near bands / golden ratio and coprime with their count: a permutation under which every
// contiguous share of the workgroups is spread over the whole image. Within a band the tiles go
// column by column, so a tile's neighbour below is marched right after it, while the volume's
// texels their rays share are still in the core's caches (in rows, a whole row of tiles
// apart). A GPU schedules workgroups dynamically and does not care.
#ifndef CUTAWAY_TILE_ORDER_H
#define CUTAWAY_TILE_ORDER_H

#include "shared/glsl_cpp.h"
#include "shared/tuning.h"

CW_NAMESPACE_BEGIN

CW_FUNC uint greatestCommonDivisor(uint a, uint b) {
    while (b != 0u) {
        uint r = a % b;
        a = b;
        b = r;
    }
    return a;
}

// The whole number nearest count / golden ratio that is coprime with `count`
// (at least 1): the host computes it once per dispatch, for the full bands.
CW_FUNC uint spreadStride(uint count) {
    uint nearest = uint(float(count) * 0.618034f + 0.5f);
    for (uint d = 0u; d <= count; ++d) {
        if (nearest > d && greatestCommonDivisor(nearest - d, count) == 1u) return nearest - d;
        if (greatestCommonDivisor(nearest + d, count) == 1u) return nearest + d;
    }
    return 1u;
}

// The item that position `position` (of `count`) takes: a permutation when
// `stride` is coprime with `count`.
CW_FUNC uint spreadOrder(uint position, uint count, uint stride) {
    return (position * stride) % count;
}

// The stride that tileOf takes for a dispatch `groups` tiles high.
CW_FUNC uint tileBandStride(uint rows) {
    return spreadStride(rows / kTileBand);
}

// The tile, relative to the dispatch's first, that workgroup `group` of
// `groups` renders: the full bands in the spread order, a partial band (the
// last kTileBand - 1 rows or fewer) last; within a band, column by column.
CW_FUNC uvec2 tileOf(uvec2 group, uvec2 groups, uint stride) {
    uint full = groups.y / kTileBand;
    uint position = group.y / kTileBand;
    uint band = position < full ? spreadOrder(position, full, stride) : position;
    uint height = min(kTileBand, groups.y - band * kTileBand);
    uint offset = (group.y - position * kTileBand) * groups.x + group.x;
    return uvec2(offset / height, band * kTileBand + offset % height);
}

// The pixel of an 8x8 tile that invocation `local` (its gl_LocalInvocationID)
// marches. lavapipe runs 8 invocations with consecutive x in lock-step: given
// a row of 8 pixels, their rays lie up to 7 pixels apart; given a block of
// 4x2, up to 3.2, and the lanes of a loop wait less for each other (8 % on
// chest_ct, docs/design/ray-caster.md#workgroups-and-tiles). Each row of 8 invocations takes a 4x2
// block; any 32 consecutive invocations (a GPU's warp) still an 8x4 block.
CW_FUNC uvec2 pixelInTile(uvec2 local) {
    return uvec2((local.x & 3u) + 4u * (local.y & 1u), (local.y & 6u) + (local.x >> 2u));
}

CW_NAMESPACE_END

#endif

// The order in which the ray caster's workgroups take the image's rows of
// 8x8-pixel tiles, and its invocations a tile's pixels. lavapipe (Mesa 22.3, lp_cs_tpool) gives
// each of its N threads one contiguous Nth of a dispatch's workgroups: in image order one core
// would march the top half of the picture and the other the bottom half, and a head whose skull
// fills one half keeps one core idle while the other finishes. Workgroup row g takes tile row (g *
// stride) mod rows instead, with a stride near rows / golden ratio and coprime with rows: a
// permutation under which every contiguous share of the workgroups is spread over the whole image.
// A GPU schedules workgroups dynamically and does not care.
#ifndef CUTAWAY_TILE_ORDER_H
#define CUTAWAY_TILE_ORDER_H

#include "shared/glsl_cpp.h"

CW_NAMESPACE_BEGIN

CW_FUNC uint greatestCommonDivisor(uint a, uint b) {
    while (b != 0u) {
        uint r = a % b;
        a = b;
        b = r;
    }
    return a;
}

// The whole number nearest rows / golden ratio that is coprime with `rows`
// (at least 1): the host computes it once per frame.
CW_FUNC uint tileRowStride(uint rows) {
    uint nearest = uint(float(rows) * 0.618034f + 0.5f);
    for (uint d = 0u; d <= rows; ++d) {
        if (nearest > d && greatestCommonDivisor(nearest - d, rows) == 1u) return nearest - d;
        if (greatestCommonDivisor(nearest + d, rows) == 1u) return nearest + d;
    }
    return 1u;
}

// The tile row that workgroup row `group` (of `rows`) renders.
CW_FUNC uint tileRowOf(uint group, uint rows, uint stride) {
    return (group * stride) % rows;
}

// The pixel of an 8x8 tile that invocation `local` (its gl_LocalInvocationID)
// marches. lavapipe runs 8 invocations with consecutive x in lock-step: given
// a row of 8 pixels, their rays lie up to 7 pixels apart; given a block of
// 4x2, up to 3.2, and the lanes of a loop wait less for each other (8 % on
// chest_ct, docs/performance.md). Each row of 8 invocations takes a 4x2 block;
// any 32 consecutive invocations (a GPU's warp) still an 8x4 block.
CW_FUNC uvec2 pixelInTile(uvec2 local) {
    return uvec2((local.x & 3u) + 4u * (local.y & 1u), (local.y & 6u) + (local.x >> 2u));
}

CW_NAMESPACE_END

#endif

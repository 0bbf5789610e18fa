// The order in which the ray caster's workgroups take the image's rows of
// 8x8-pixel tiles. lavapipe (Mesa 22.3, lp_cs_tpool) gives each of its N
// threads one contiguous Nth of a dispatch's workgroups: in image order one
// core would march the top half of the picture and the other the bottom half,
// and a head whose skull fills one half keeps one core idle while the other
// finishes. Workgroup row g takes tile row (g * stride) mod rows instead, with
// a stride near rows / golden ratio and coprime with rows: a permutation under
// which every contiguous share of the workgroups is spread over the whole
// image. A GPU schedules workgroups dynamically and does not care.
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

CW_NAMESPACE_END

#endif

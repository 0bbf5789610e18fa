// Whether a sample, or a slab between two values, may show: the ray caster's
// test at every sample it fetches, as arithmetic on at most CW_VISIBLE_RUNS
// runs of visible bins (VisibleValues::runs, render/skipping/occupancy.hpp). A table
// lookup per sample was a storage-buffer read, which lavapipe makes lane by
// lane; the runs are read once per ray (docs/design/ray-caster.md#the-march).
#ifndef CUTAWAY_VISIBLE_RUNS_H
#define CUTAWAY_VISIBLE_RUNS_H

#include "shared/glsl_cpp.h"

#define CW_VISIBLE_RUNS 4

CW_NAMESPACE_BEGIN

// The visible bins as runs [lo[i], hi[i]) (empty: lo = hi) of a table of
// `bins` entries: the ray caster's storage buffer (std430), read once per ray.
struct VisibleRuns {
    ivec4 lo;
    ivec4 hi;
    int bins;
    int pad0, pad1, pad2; // std430 rounds the struct up to its 16-byte alignment
};

// Whether some bin that a slab from value `front` to `back` (normalized; the
// same for a sample) reads through the table's linear filter, from
// floor(min * (bins - 1)) to ceil(max * (bins - 1)), lies in a run [lo[i],
// hi[i]) of visible bins (an empty run: lo = hi).
CW_FUNC bool runsMayShow(ivec4 lo, ivec4 hi, int bins, float front, float back) {
    float last = float(bins - 1);
    int first = clamp(int(floor(min(front, back) * last)), 0, bins - 1);
    int end = clamp(int(ceil(max(front, back) * last)), 0, bins - 1) + 1;
    return any(lessThan(max(lo, ivec4(first)), min(hi, ivec4(end))));
}

CW_NAMESPACE_END

#ifdef __cplusplus
static_assert(offsetof(cutaway::shader::VisibleRuns, hi) == 16);
static_assert(offsetof(cutaway::shader::VisibleRuns, bins) == 32);
static_assert(sizeof(cutaway::shader::VisibleRuns) == 48);
#endif

#endif

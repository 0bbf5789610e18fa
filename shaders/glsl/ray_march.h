// GLSL only: the ray caster (render.method "raycast", docs/design/ray-caster.md):
// one invocation per pixel marches its ray front to back, taking its samples
// where the ray crosses the slicing planes s_k = (k + 0.5) * spacing, so it
// samples exactly where slicing would and calls the same per-sample code
// (sample_common.h, operator_sample.h). What it saves over slicing: a slab's
// back is the next slab's front (one volume fetch, or one resolve of Eq. 3-4
// in an operator's box, per sample instead of two), no rasterization or
// blending, and a ray stops the moment it is opaque. It also steps over empty
// cells, and takes the gradient and lighting only at visible slabs: lavapipe
// runs 8 rays in lock-step and pays for both sides of a branch, but a loop
// ends when all its lanes leave it, so transparent runs are inner loops of
// their own. Built with CW_YIELD_LANES (the shaders' "lanes" flavour, used
// on CPU devices: gpu/device_tuning.hpp), the lanes still
// in such a loop stop for a pass of shading as soon as one lane of their
// subgroup waits at a visible slab, instead of all waiting for the last.
//
// raycast.comp.glsl renders the untouched volume; raycast_operators.comp.glsl
// defines CW_RAY_OPERATORS: up to CW_RAY_MAX_OPERATORS operators, each one's
// descriptor set (the slicing shader's set 1) bound as set 1 + slot for its
// map and feature field, their uniforms side by side in set 0. A ray
// splits into runs of samples: those in an operator's deformed box (the
// operator's proxy; the boxes do not overlap) take that operator's slabs,
// the others the untouched volume's, as slicing's stencil decides.
// raycast_operator.comp.glsl defines
// CW_RAY_ONE_OPERATOR too: the shader for one operator, without the loop
// over two or three boxes. lavapipe keeps every shader's NIR, dead code and
// all, as long as its pipeline lives; that loop's three copies of the
// operator's code took 25-38 MiB of the frog's peak
// (docs/design/lavapipe.md#compilation-and-memory).
#ifndef CUTAWAY_RAY_MARCH_H
#define CUTAWAY_RAY_MARCH_H

#ifdef CW_RAY_OPERATORS
#include "glsl/operator_sample.h"
#else
#include "glsl/sample_common.h"
#endif
#include "shared/ray_push.h"
#include "shared/tile_order.h"
#include "shared/visible_runs.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
// The census (VolumeRenderer::setCensus, bench --census): the target receives,
// instead of colour, how many samples the ray took of each kind: x the
// untouched volume's values fetched, y its slabs shaded, z operator points
// resolved (Eq. 3-4), w operator slabs shaded. Off, the counting folds away.
layout(constant_id = CW_SPEC_CENSUS) const bool cwCensus = false;
vec4 census = vec4(0.0);
layout(set = 0, binding = CW_BIND_RAY_TARGET, rgba32f) uniform writeonly image2D target;
// What the pixel's first visible sample was, as slicing's id attachment
// (slice_common.h): which proxy it came from (codes: see CW_ID_BACKGROUND in
// sample_common.h), its distance from the eye and its label's code.
layout(set = 0, binding = CW_BIND_RAY_ID, rgba32f) uniform writeonly image2D idTarget;
// With cwMattes, the mattes (slots 1..3 in layer 0, 4..6 in layer 1, alpha
// the pixel's), as slicing's matte attachments.
layout(set = 0, binding = CW_BIND_RAY_MATTES, rgba32f) uniform writeonly image2DArray matteTarget;
// The depth of the scene's opaque meshes (render/mesh_pass.hpp), drawn before
// the rays; 1 (the far plane) where there are none. A sample counts when it
// lies in front of them or at their depth, as slicing's depth test decides.
layout(set = 0, binding = CW_BIND_RAY_MESH_DEPTH) uniform sampler2D meshDepth;

// What a ray leaves besides its colour: `first` its first visible sample's
// proxy code, distance and label code (the id target), and the mattes.
struct RayAovs {
    vec4 first;
    vec3 mattes0, mattes1;
};

// Composites slab colour `c` from proxy `code`, taken at world point `at`
// (its material from texture coordinate `tc`), behind `sum`; the first
// visible one names the pixel's proxy.
void composite(vec4 c, float code, vec3 at, vec3 tc, inout vec4 sum, inout RayAovs aov) {
    if (aov.first.x == 0.0 && c.a >= CW_ID_MIN_ALPHA)
        aov.first = vec4(code, slabDepth(at), labelCode(tc), 1.0);
    if (cwMattes && c.a > 0.0) {
        vec3 first, second;
        matteShares(tc, (1.0 - sum.a) * c.a, first, second);
        aov.mattes0 += first;
        aov.mattes1 += second;
    }
    sum += (1.0 - sum.a) * c;
}
// One texel per cell of kRayCellVoxels^3 (render/skipping/ray_cells.hpp): 0 where the
// cell is occupied; else r, and every cell within r - 1 of it (chessboard
// distance) is empty: each sample there, and each slab up to the margin long
// that starts there, is transparent.
layout(set = 0, binding = CW_BIND_RAY_CELLS, r8ui) uniform readonly uimage3D cellImage;
// Which bins of the classification tables any layer shows, as runs
// (VisibleValues::runs, render/skipping/occupancy.hpp; shared/visible_runs.h).
// Transparent runs ask only that; the table is read once a slab may show.
layout(std430, set = 0, binding = CW_BIND_RAY_VISIBLE) readonly buffer Visible {
    VisibleRuns visible;
};
// The runs, read at the start of main while every lane runs it: lavapipe
// then reads each word once, where a read in the march's loops is made lane
// by lane (a lane may have left).
ivec4 runLo, runHi;
int runBins;
layout(push_constant) uniform Ray {
    RayPush ray;
};

uvec2 unpackTile(uint packed) {
    return uvec2(packed & 0xffffu, packed >> 16);
}

// One ray: where it starts and goes, and its samples k (whole numbers) at
// p(k) = origin + dir * t(k) on the slicing planes.
struct March {
    vec3 origin, dir, toEye;
    Viewer viewer;   // viewerOf(toEye): the lights' half vectors, once per ray
    float obliquity; // 1 / cos of the angle between the ray and the view
    float spacing;   // between the planes, along the view (mm)
    float so, fd;    // the origin's and the direction's distance along the view
    float first;     // the first sample; tcFirst is its texture coordinate
    vec3 tcFirst, tcStep;
    bool slabsInMargin; // the ray's slabs are no longer than the cells' margin
};

vec3 pointAt(March m, float k) {
    return m.origin + m.dir * (((k + 0.5) * m.spacing - m.so) / m.fd);
}

// The samples whose points lie between ray parameters t0 and t1: (first, last),
// first > last when there are none.
vec2 samplesBetween(March m, float t0, float t1) {
    return vec2(ceil((m.so + t0 * m.fd) / m.spacing - 0.5),
                floor((m.so + t1 * m.fd) / m.spacing - 0.5));
}

// The ray parameters where it enters and leaves the box [lo, hi], along the
// ray origin + t * dir, from t = 0 on.
vec2 rayThroughBox(vec3 origin, vec3 dir, vec3 lo, vec3 hi) {
    vec3 inv = 1.0 / dir;
    vec3 ta = (lo - origin) * inv, tb = (hi - origin) * inv;
    vec3 tMin = min(ta, tb), tMax = max(ta, tb);
    return vec2(max(max(tMin.x, tMin.y), max(tMin.z, 0.0)), min(min(tMax.x, tMax.y), tMax.z));
}

// How many steps (of `step` cells each; `invStep` its reciprocal, 0 where it
// is 0) a ray at `at` (in cells, inside `cell`) takes to leave the cube of
// empty cells [cell - (r - 1), cell + r): the first sample past its wall, at
// least 1. A multiplication by the ray's reciprocal instead of three
// divisions per sample (lavapipe runs this for every sample its lanes take);
// the product may round up past a whole number, so a hair is taken off before
// rounding up: the step may land one sample short of the wall, never past it.
float stepsToLeave(vec3 at, ivec3 cell, uint r, vec3 step, vec3 invStep) {
    vec3 wall =
        vec3(cell) + mix(vec3(1.0 - float(r)), vec3(float(r)), greaterThan(step, vec3(0.0)));
    vec3 toWall = mix(vec3(1e30), (wall - at) * invStep, notEqual(invStep, vec3(0.0)));
    return max(1.0, ceil(min(toWall.x, min(toWall.y, toWall.z)) - 1e-4));
}

// The reciprocal of each component of `step` (in cells), 0 where the ray does
// not move along that axis.
vec3 reciprocalStep(vec3 step) {
    return mix(vec3(0.0), 1.0 / step, greaterThan(abs(step), vec3(1e-12)));
}

// How many steps of `tcStep` from `tc` until the ray leaves the cube of empty
// cells around the cell it is in, when that cell is empty and the ray's slabs
// are no longer than the cells' margin; 0 otherwise. Never steps past a sample
// outside the cube, so it skips only samples (and the slabs they start) that
// the cells say are transparent. `cellStep`: tcStep in cells, `invCellStep`
// its reciprocal (reciprocalStep).
float stepsOverEmpty(vec3 tc, vec3 cellStep, vec3 invCellStep, bool slabsInMargin) {
    vec3 at = tc * ray.cellsPerTexture.xyz;
    ivec3 cell = clamp(ivec3(floor(at)), ivec3(0), imageSize(cellImage) - 1);
    uint free = imageLoad(cellImage, cell).r;
    if (!slabsInMargin || free == 0u) return 0.0;
    return stepsToLeave(at, cell, free, cellStep, invCellStep);
}

// Whether a slab from value `front` to `back` may show: some bin of the table
// between them (and their neighbours: the lookup filters) is visible for
// some classification. Conservative where the lookup is exact, and where
// the runs join gaps (VisibleValues::runs); arithmetic instead of a table
// read per sample (docs/design/ray-caster.md#the-march).
bool mayShow(float front, float back) {
    return runsMayShow(runLo, runHi, runBins, front, back);
}

#ifdef CW_YIELD_LANES
// How many lanes of the subgroup run this code.
uint lanesHere() {
    return subgroupBallotBitCount(subgroupBallot(true));
}

// Whether the lanes still stepping over transparent samples should stop
// for a pass of shading, at the start of each of their passes: as soon as
// one of the `live` lanes that began stepping (the most seen in this loop's
// passes so far) waits at a visible slab or is done. Their rays are
// unchanged: the stopped lanes go on stepping after the pass.
bool yieldToShading(inout uint live) {
    uint here = lanesHere();
    live = max(live, here);
    return here < live;
}
#endif

// Samples k0..k1 of the untouched volume, composited into `sum`.
void backgroundRun(March m, float k0, float k1, inout vec4 sum, inout RayAovs aov) {
    float k = k0;
    vec3 tc = m.tcFirst + (k0 - m.first) * m.tcStep;
    vec3 tcStep = m.tcStep;
    vec3 cellStep = tcStep * ray.cellsPerTexture.xyz;
    vec3 invCellStep = reciprocalStep(cellStep);
    float front = volumeAt(tc);
    bool haveFront = true; // false after stepping over empty cells
    while (k <= k1) {
        // Transparent slabs cost a volume fetch and a visibility test
        // (mayShow), empty cells a cell lookup; the whole table texel, the
        // gradient and the lighting run once every lane is at a visible slab
        // or done (with CW_YIELD_LANES: once one of them is).
        float next = 0.0;
        bool visible = false;
#ifdef CW_YIELD_LANES
        uint live = 0u;
#endif
        while (k <= k1) {
#ifdef CW_YIELD_LANES
            if (yieldToShading(live)) break;
#endif
            // Jumps over empty cells take passes of their own, repeated
            // while some lane still jumps: lavapipe runs a loop's whole body
            // for its 8 lanes on every pass, so a jump in the pass below
            // would cost its lanes the fetch and the test of the others.
            float skip;
            do {
                skip = k <= k1 ? stepsOverEmpty(tc, cellStep, invCellStep, m.slabsInMargin) : 0.0;
                k += skip;
                tc += skip * tcStep;
                haveFront = haveFront && skip == 0.0;
            } while (skip > 0.0);
            if (k > k1) break;
            float value = volumeAt(haveFront ? tc + tcStep : tc);
            if (cwCensus) census.x += 1.0;
            if (!haveFront) {
                front = value;
                haveFront = true;
                continue;
            }
            next = value;
            if (mayShow(front, cwPreintegrated ? next : front)) {
                visible = true;
                break;
            }
            tc += tcStep;
            front = next;
            k += 1.0;
        }
        if (k > k1) break;
        if (!visible) continue;
        if (cwCensus) census.y += 1.0;
        float back = cwPreintegrated ? next : front;
        vec4 c = classifySlab(front, back, m.obliquity, classLayer(tc));
        if (c.a > 0.0) c = backgroundSlab(c, front, back, tc, tcStep, m.viewer, m.obliquity);
        composite(c, CW_ID_BACKGROUND, pointAt(m, k), tc, sum, aov);
        if (sum.a >= u.termination.x) break;
        tc += tcStep;
        front = next;
        k += 1.0;
    }
}

#ifdef CW_RAY_OPERATORS
layout(set = 0, binding = CW_BIND_RAY_BLOCKS, r8ui) uniform readonly uimage3D blocks0;
layout(set = 0, binding = CW_BIND_RAY_BLOCKS + 1, r8ui) uniform readonly uimage3D blocks1;
layout(set = 0, binding = CW_BIND_RAY_BLOCKS + 2, r8ui) uniform readonly uimage3D blocks2;
// Slot `slot`'s block texel at `block` (clamped), and the blocks' size. GLSL
// takes no image with a format as a parameter; each call passes a constant,
// so the compiler keeps one load.
uint blockAt(int slot, ivec3 block) {
    if (slot == 0) return imageLoad(blocks0, clamp(block, ivec3(0), imageSize(blocks0) - 1)).r;
    if (slot == 1) return imageLoad(blocks1, clamp(block, ivec3(0), imageSize(blocks1) - 1)).r;
    return imageLoad(blocks2, clamp(block, ivec3(0), imageSize(blocks2) - 1)).r;
}

// How many samples from `k` on lie in the cube of empty blocks of the
// operator around the block that p(k) is in (render/skipping/operator_regions.hpp:
// blocks of map texels where the operator shader, reading up to a slab from
// its point, shows nothing; each holds its chessboard distance r to the
// nearest active block, 0 when active): 0 when that block is active. Like
// stepsOverEmpty, never past a sample outside the cube.
// `blockStep`: the step from one sample to the next, in blocks.
float stepsOverEmptyBlocks(OperatorUniforms op, int slot, March m, float k, vec3 blockStep,
                           vec3 invBlockStep) {
    vec3 q = (op.worldToLocal * vec4(pointAt(m, k), 1.0)).xyz;
    vec3 at = (q - op.mapLo.xyz) / (op.mapHi.xyz - op.mapLo.xyz) * op.blocks.xyz;
    ivec3 block = ivec3(floor(at));
    uint free = blockAt(slot, block);
    if (free == 0u) return 0.0;
    return stepsToLeave(at, block, free, blockStep, invBlockStep);
}

// Samples k0..k1, all in the operator's deformed box, composited into `sum`.
// Each resolves one point: a slab's back is the next one's front.
void operatorRun(OperatorUniforms op, sampler3D map, sampler3D derivatives, sampler3D feature,
                 int slot, int mode, March m, float k0, float k1, inout vec4 sum,
                 inout RayAovs aov) {
    float stepMm = m.spacing * m.obliquity;
    vec3 blockStep = mat3(op.worldToLocal) * (m.dir * (m.spacing / m.fd)) /
                     (op.mapHi.xyz - op.mapLo.xyz) * op.blocks.xyz;
    vec3 invBlockStep = reciprocalStep(blockStep);
    float k = k0;
    Resolved front;
    bool haveFront = false; // false at first and after stepping over empty blocks
    while (k <= k1) {
        // Empty blocks cost a block lookup, transparent slabs a resolve and a
        // visibility test (mayShow).
        Resolved next;
        Slab s;
        bool visible = false;
#ifdef CW_YIELD_LANES
        uint live = 0u;
#endif
        // One resolve per pass for every lane (of the front after a jump, or
        // of the next back), so lanes in lock-step keep together.
        while (k <= k1) {
#ifdef CW_YIELD_LANES
            if (yieldToShading(live)) break;
#endif
            // Jumps over empty blocks in passes of their own (as in
            // backgroundRun): a resolve costs several fetches.
            float skip;
            do {
                skip =
                    k <= k1 ? stepsOverEmptyBlocks(op, slot, m, k, blockStep, invBlockStep) : 0.0;
                k += skip;
                haveFront = haveFront && skip == 0.0;
            } while (skip > 0.0);
            if (k > k1) break;
            next = resolve(op, map, feature, slot, mode, pointAt(m, haveFront ? k + 1.0 : k));
            if (cwCensus) census.z += 1.0;
            if (!haveFront) {
                front = next;
                haveFront = true;
                continue;
            }
            s = operatorSlab(mode, front, cwPreintegrated ? next : front);
            if (!s.empty && mayShow(s.frontValue, s.backValue)) {
                visible = true;
                break;
            }
            front = next;
            k += 1.0;
        }
        if (k > k1) break;
        if (!visible) continue;
        bool moved;
        if (cwCensus) census.w += 1.0;
        vec3 at = pointAt(m, k);
        vec3 source;
        vec4 c = refinedOperatorSlab(op, map, derivatives, feature, slot, mode, front,
                                     cwPreintegrated ? next : front, at, pointAt(m, k + 1.0) - at,
                                     m.viewer, m.obliquity, stepMm, moved, source);
        composite(c, moved ? op.band.y : CW_ID_BACKGROUND, at, source, sum, aov);
        if (sum.a >= u.termination.x) break;
        front = next;
        k += 1.0;
    }
}

layout(constant_id = CW_SPEC_OPERATOR_COUNT) const
    int cwOperatorCount = 1; // 1..CW_RAY_MAX_OPERATORS
layout(constant_id = CW_SPEC_ALIGNMENT1) const
    int cwAlignment1 = 0; // slot 1's CW_ALIGN_*; slot 0's
layout(constant_id = CW_SPEC_ALIGNMENT2) const int cwAlignment2 = 0; // is cwAlignment
// The slots' uniforms, all in one buffer of set 0 (lavapipe, Mesa 22.3,
// crashed reading a fourth uniform buffer in a compute shader), and a storage
// buffer: from a uniform buffer, lavapipe inlined the values that steer
// branches and compiled the shader again at every dispatch, keeping each copy
// (about 1 MB a frame; GpuTest.RepeatedFramesCompileNothingNew).
layout(std140, set = 0, binding = CW_BIND_RAY_OPERATORS) readonly buffer RayOperators {
    OperatorUniforms ops[CW_RAY_MAX_OPERATORS];
}
slots;
layout(set = 1, binding = CW_BIND_OP_MAP) uniform sampler3D map0;
layout(set = 1, binding = CW_BIND_OP_FEATURE) uniform sampler3D feature0;
layout(set = 1, binding = CW_BIND_OP_DERIVATIVES) uniform sampler3D derivatives0;
layout(set = 2, binding = CW_BIND_OP_MAP) uniform sampler3D map1;
layout(set = 2, binding = CW_BIND_OP_FEATURE) uniform sampler3D feature1;
layout(set = 2, binding = CW_BIND_OP_DERIVATIVES) uniform sampler3D derivatives1;
layout(set = 3, binding = CW_BIND_OP_MAP) uniform sampler3D map2;
layout(set = 3, binding = CW_BIND_OP_FEATURE) uniform sampler3D feature2;
layout(set = 3, binding = CW_BIND_OP_DERIVATIVES) uniform sampler3D derivatives2;
// Each slot's blocks' distances (see stepsOverEmptyBlocks).

// Samples first..last of both runs `a` and `b` (first > last: none).
vec2 unite(vec2 a, vec2 b) {
    if (b.x > b.y) return a;
    return a.x <= a.y ? vec2(min(a.x, b.x), max(a.y, b.y)) : b;
}

// The run of samples from k on: in slot i's box (its samples `box`), or up to
// the first box that starts after k.
void runFrom(float k, vec2 box, int i, inout int slot, inout float end) {
    if (k >= box.x && k <= box.y) {
        slot = i;
        end = box.y; // the boxes do not overlap: no other starts before it ends
    } else if (box.x > k && box.x <= box.y) {
        end = min(end, box.x - 1.0);
    }
}

// The samples in the operator's deformed box up to ray parameter tEnd, as
// samplesBetween.
vec2 operatorSamples(OperatorUniforms op, March m, float tEnd) {
    vec3 origin = (op.worldToLocal * vec4(m.origin, 1.0)).xyz;
    vec3 dir = mat3(op.worldToLocal) * m.dir; // the same t: the map is affine
    vec2 t = rayThroughBox(origin, dir, op.mapLo.xyz, op.mapHi.xyz);
    t.y = min(t.y, tEnd);
    return t.x < t.y ? samplesBetween(m, t.x, t.y) : vec2(1.0, 0.0);
}

// The ray's samples first..last (`samples`): those in an operator's box
// (`box0`..`box2`, as operatorSamples) take its slabs, the others the
// untouched volume's where they lie in `volume`.
void marchWithOperators(March m, vec2 samples, vec2 volume, vec2 box0, vec2 box1, vec2 box2,
                        inout vec4 sum, inout RayAovs aov) {
    if (cwOperatorCount == 1) {
        // One box: the untouched volume before it, the box, the volume
        // after it. Three calls rather than the loop below: lavapipe runs
        // every call's code on each pass of a loop, masked where no lane
        // takes it, and an operator's resolve and shading cost as much as
        // tens of the untouched volume's samples (ct_head's peel: 10-25 %
        // of the frame).
        bool hit = box0.x <= box0.y;
        float before = hit ? box0.x - 1.0 : samples.y;
        float after = hit ? box0.y + 1.0 : samples.y + 1.0;
        backgroundRun(m, max(samples.x, volume.x), min(before, volume.y), sum, aov);
        if (sum.a < u.termination.x)
            operatorRun(slots.ops[0], map0, derivatives0, feature0, 0, cwAlignment, m, box0.x,
                        box0.y, sum, aov);
        if (sum.a < u.termination.x) backgroundRun(m, max(after, volume.x), volume.y, sum, aov);
    }
#ifndef CW_RAY_ONE_OPERATOR
    else {
        // Each pass: the untouched volume up to the next box, then that box
        // (as many passes as boxes the ray meets, plus one).
        float k = samples.x;
        while (k <= samples.y && sum.a < u.termination.x) {
            int slot = -1;
            float end = samples.y;
            runFrom(k, box0, 0, slot, end);
            runFrom(k, box1, 1, slot, end);
            runFrom(k, box2, 2, slot, end);
            if (slot < 0) {
                backgroundRun(m, max(k, volume.x), min(end, volume.y), sum, aov);
                k = end + 1.0;
                if (k > samples.y || sum.a >= u.termination.x) break;
                end = samples.y;
                runFrom(k, box0, 0, slot, end);
                runFrom(k, box1, 1, slot, end);
                runFrom(k, box2, 2, slot, end);
            }
            if (slot == 0) {
                operatorRun(slots.ops[0], map0, derivatives0, feature0, 0, cwAlignment, m, k, end,
                            sum, aov);
            } else if (cwOperatorCount > 1 && slot == 1) {
                operatorRun(slots.ops[1], map1, derivatives1, feature1, 1, cwAlignment1, m, k, end,
                            sum, aov);
            } else if (cwOperatorCount > 2 && slot == 2) {
                operatorRun(slots.ops[2], map2, derivatives2, feature2, 2, cwAlignment2, m, k, end,
                            sum, aov);
            }
            k = end + 1.0;
        }
    }
#endif
}
#endif

void main() {
    runLo = visible.lo;
    runHi = visible.hi;
    runBins = visible.bins;
    // Workgroups take bands of tiles in an order that spreads each core's
    // share over the image, and each 8 invocations a 4x2 block of pixels
    // (shared/tile_order.h).
    uvec2 tile =
        tileOf(gl_WorkGroupID.xy, gl_NumWorkGroups.xy, ray.bandStride) + unpackTile(ray.tileOffset);
#ifndef CW_RAY_OPERATORS
    // Frames with operators run this shader over the image but the tiles
    // their boxes may cover (Raycaster::record). lavapipe runs every part of
    // a shader at least once per 8 rays, masked where no ray takes it: an
    // operator's resolve and shading, run so once, cost rays that meet no
    // box a sixth of ct_head's frame (187 ms against 217 with the box out of
    // view, docs/design/lavapipe.md#eight-lanes-in-lock-step).
    if (all(greaterThanEqual(tile, unpackTile(ray.operatorTilesLo))) &&
        all(lessThan(tile, unpackTile(ray.operatorTilesHi))))
        return;
#endif
    ivec2 pixel = ivec2(tile * gl_WorkGroupSize.xy + pixelInTile(gl_LocalInvocationID.xy));
    ivec2 size = imageSize(target);
    if (pixel.x >= size.x || pixel.y >= size.y) return;
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(size) * 2.0 - 1.0;
    vec4 nearH = ray.clipToWorld * vec4(ndc, 0.0, 1.0);
    vec4 farH = ray.clipToWorld * vec4(ndc, 1.0, 1.0);
    March m;
    m.origin = nearH.xyz / nearH.w; // on the near plane: nothing in front of it is drawn
    m.dir = normalize(farH.xyz / farH.w - m.origin);
    m.toEye = -m.dir;
    m.viewer = viewerOf(m.toEye, u);
    m.obliquity = obliquityOf(m.toEye);
    m.spacing = u.viewDir.w;
    m.fd = dot(u.viewDir.xyz, m.dir);
    // The pixel's samples lie this far behind the planes (shared/sampling.h):
    // the lattice moves by it along the view.
    m.so = dot(u.viewDir.xyz, m.origin) - sampleOffset(vec2(pixel) + 0.5, u.sampling) * m.spacing;

    // The untouched volume's samples: those in the occupied cells' bounds.
    vec2 t = rayThroughBox(m.origin, m.dir, ray.boxLo.xyz, ray.boxHi.xyz);
    // The meshes' depth ends the ray.
    float depth = textureLod(meshDepth, (vec2(pixel) + 0.5) / vec2(size), 0.0).r;
    vec4 meshH = ray.clipToWorld * vec4(ndc, depth, 1.0);
    float tMesh = depth < 1.0 ? dot(meshH.xyz / meshH.w - m.origin, m.dir) : 1e30;
    t.y = min(t.y, tMesh);
    vec2 volume = t.x < t.y ? samplesBetween(m, t.x, t.y) : vec2(1.0, 0.0);
    vec2 samples = volume;
#ifdef CW_RAY_OPERATORS
    vec2 box0 = operatorSamples(slots.ops[0], m, tMesh);
    vec2 box1 = cwOperatorCount > 1 ? operatorSamples(slots.ops[1], m, tMesh) : vec2(1.0, 0.0);
    vec2 box2 = cwOperatorCount > 2 ? operatorSamples(slots.ops[2], m, tMesh) : vec2(1.0, 0.0);
    samples = unite(unite(unite(samples, box0), box1), box2);
#endif
    vec4 sum = vec4(0.0);
    RayAovs aov = RayAovs(vec4(0.0), vec3(0.0), vec3(0.0));
    if (samples.x <= samples.y) {
        m.first = samples.x;
        vec3 p = pointAt(m, m.first);
        m.tcFirst = toTexture(p);
        m.tcStep = toTexture(p + m.dir * (m.spacing * m.obliquity)) - m.tcFirst;
        // The cells cover slabs up to cellsPerTexture.w voxels long.
        vec3 voxelStep = abs(m.tcStep) * vec3(textureSize(volumeTex, 0));
        m.slabsInMargin = max(voxelStep.x, max(voxelStep.y, voxelStep.z)) <= ray.cellsPerTexture.w;
#ifdef CW_RAY_OPERATORS
        marchWithOperators(m, samples, volume, box0, box1, box2, sum, aov);
#else
        backgroundRun(m, samples.x, samples.y, sum, aov);
#endif
    }
    imageStore(target, pixel, cwCensus ? census : sum);
    imageStore(idTarget, pixel, aov.first);
    if (cwMattes) {
        imageStore(matteTarget, ivec3(pixel, 0), vec4(aov.mattes0, sum.a));
        imageStore(matteTarget, ivec3(pixel, 1), vec4(aov.mattes1, sum.a));
    }
}

#endif

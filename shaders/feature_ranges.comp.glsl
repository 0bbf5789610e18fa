#version 460
// The range of a feature field over each cell (FieldRangeParams in
// shared/feature_bake.h): the texels a trilinear sample in the cell can
// weigh, its voxels and one more on every side, clamped to the grid. One
// invocation per two cells side by side in x, marching their column of cells
// along z: neighbouring cells share voxels, and this way each plane of the
// column is read once for both cells and kept for the next cell up, 24 loads
// a cell of 2^3 instead of 64 (lavapipe loads texels one lane at a time).
#extension GL_GOOGLE_include_directive : require
#include "shared/feature_bake.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(set = 0, binding = CW_RANGES_BIND_FIELD, r16f) uniform readonly image3D field;
layout(set = 0, binding = CW_RANGES_BIND_OUT, rg8i) uniform writeonly iimage3D ranges;
layout(push_constant) uniform Push {
    FieldRangeParams params;
};

// Ranges of the two cells' windows (xy: the first's, zw: the second's), min
// and max.
struct Pair {
    vec2 a, b;
};

Pair merge(Pair p, Pair q) {
    return Pair(vec2(min(p.a.x, q.a.x), max(p.a.y, q.a.y)),
                vec2(min(p.b.x, q.b.x), max(p.b.y, q.b.y)));
}

// Plane z of the two cells' windows: x from x0 - 1 (the first cell's) to
// x0 + 2 cellVoxels (the second's), y over the cells' row and one more on
// each side.
Pair plane(int x0, int y0, int z) {
    int v = params.cellVoxels;
    int zc = clamp(z, 0, params.dims.z - 1);
    Pair p = Pair(vec2(1e30, -1e30), vec2(1e30, -1e30));
    for (int y = y0 - 1; y <= y0 + v; ++y) {
        int yc = clamp(y, 0, params.dims.y - 1);
        for (int i = 0; i <= 2 * v + 1; ++i) {
            float t = imageLoad(field, ivec3(clamp(x0 - 1 + i, 0, params.dims.x - 1), yc, zc)).r;
            if (i <= v + 1) p.a = vec2(min(p.a.x, t), max(p.a.y, t));
            if (i >= v) p.b = vec2(min(p.b.x, t), max(p.b.y, t));
        }
    }
    return p;
}

void main() {
    ivec3 n = imageSize(ranges);
    ivec2 cell = ivec2(2 * gl_GlobalInvocationID.x, gl_GlobalInvocationID.y);
    if (cell.x >= n.x || cell.y >= n.y) return;
    int v = params.cellVoxels;
    int x0 = cell.x * v, y0 = cell.y * v;
    // The two planes below each cell's own (z0 - 1 and z0): the last two of
    // the cell before it.
    Pair below = plane(x0, y0, -1), at = plane(x0, y0, 0);
    for (int cz = 0; cz < n.z; ++cz) {
        Pair sum = merge(below, at);
        Pair last = at, beforeLast = below;
        for (int k = 1; k <= v; ++k) {
            Pair p = plane(x0, y0, cz * v + k);
            sum = merge(sum, p);
            beforeLast = last;
            last = p;
        }
        below = beforeLast;
        at = last;
        imageStore(ranges, ivec3(cell, cz),
                   ivec4(encodeFieldRange(sum.a.x, sum.a.y, params.scale), 0, 0));
        if (cell.x + 1 < n.x)
            imageStore(ranges, ivec3(cell.x + 1, cell.y, cz),
                       ivec4(encodeFieldRange(sum.b.x, sum.b.y, params.scale), 0, 0));
    }
}

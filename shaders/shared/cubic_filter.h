// The tricubic filter of /render/filter "cubic": Catmull-Rom's interpolating
// cubic (Keys' kernel with a = -1/2), separable over the 4^3 texels around a
// sample. Along one axis, at texel-space position x (texel i's centre at
// i + 0.5), it weighs the texels floor(x - 0.5) - 1 .. + 2 by the weights of
// t = fract(x - 0.5).
//
// Why this kernel (docs/quality.md has the figures): it passes through the
// voxels' own values and reproduces polynomials up to quadratics exactly,
// so a thin structure keeps its contrast and a thick-slice scan loses its
// terraces. The cubic B-spline (eight trilinear fetches, Sigg and Hadwiger
// 2005) is smoother but blurs by a third of a voxel's variance: rendering
// ct_head kept every third slice, it moved further from the full scan than
// trilinear filtering did, where Catmull-Rom came closer. An interpolating
// B-spline would need a prefilter and values outside the window's range.
//
// Catmull-Rom's negative lobes overshoot at sharp edges. The values are held
// to the range of the eight texels of the sample's cell (as trilinear
// filtering's are), which takes away the ringing at CT's bone edges and
// lets empty-space skipping keep the cell's reach. Gradients are not held.
#ifndef CUTAWAY_CUBIC_FILTER_H
#define CUTAWAY_CUBIC_FILTER_H

#include "shared/glsl_cpp.h"

CW_NAMESPACE_BEGIN

// The weights of texels floor(x - 0.5) - 1, + 0, + 1, + 2 for fraction t.
CW_FUNC vec4 catmullRomWeights(float t) {
    float t2 = t * t;
    float t3 = t2 * t;
    return vec4(-t3 + 2.0f * t2 - t, 3.0f * t3 - 5.0f * t2 + 2.0f, -3.0f * t3 + 4.0f * t2 + t,
                t3 - t2) *
           0.5f;
}

// Where a sample at texture coordinate tc of a grid of `dims` texels reads:
// along each axis the indices of its four texels, clamped to the grid as a
// sampler clamps to the edge, and their four weights.
struct CubicCell {
    ivec4 ix;
    ivec4 iy;
    ivec4 iz;
    vec4 wx;
    vec4 wy;
    vec4 wz;
};

CW_FUNC ivec4 cubicIndices(int first, int size) {
    return clamp(ivec4(first) + ivec4(0, 1, 2, 3), ivec4(0), ivec4(size - 1));
}

CW_FUNC CubicCell cubicCell(vec3 tc, ivec3 dims) {
    vec3 x = tc * vec3(dims) - 0.5f;
    vec3 i = floor(x);
    vec3 t = x - i;
    ivec3 first = ivec3(i) - 1;
    CubicCell c;
    c.ix = cubicIndices(first.x, dims.x);
    c.iy = cubicIndices(first.y, dims.y);
    c.iz = cubicIndices(first.z, dims.z);
    c.wx = catmullRomWeights(t.x);
    c.wy = catmullRomWeights(t.y);
    c.wz = catmullRomWeights(t.z);
    return c;
}

// Whether texel (x, y, z) of the 4^3 (0..3 each) is one of the eight of the
// sample's cell, whose range the values are held to.
CW_FUNC bool inCubicCell(int x, int y, int z) {
    return (x == 1 || x == 2) && (y == 1 || y == 2) && (z == 1 || z == 2);
}

CW_NAMESPACE_END

#endif

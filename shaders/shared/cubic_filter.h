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
// the first of its 4^3 texels (`first`, before clamping to the grid) and
// each axis's four weights.
struct CubicCell {
    ivec3 first;
    vec4 wx;
    vec4 wy;
    vec4 wz;
};

CW_FUNC CubicCell cubicCell(vec3 tc, ivec3 dims) {
    vec3 x = tc * vec3(dims) - 0.5f;
    vec3 i = floor(x);
    vec3 t = x - i;
    CubicCell c;
    c.first = ivec3(i) - 1;
    c.wx = catmullRomWeights(t.x);
    c.wy = catmullRomWeights(t.y);
    c.wz = catmullRomWeights(t.z);
    return c;
}

CW_NAMESPACE_END

#endif

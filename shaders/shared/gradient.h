// Gradient encoding, shared by the bake shader and its CPU reference.
// The gradient is taken with Farid and Simoncelli's matched 3-tap pair
// (Differentiation of discrete multidimensional signals, IEEE TIP 2004): the
// central difference along each axis, prefiltered with [p1 p0 p1] across
// each of the other two, the weights chosen so the gradient's direction
// depends least on its orientation to the grid. Sobel's [1 2 1] / 4 turned
// the direction of an oblique surface with the surface's place between
// voxels, which specular light showed as rings; plain central differences
// show a voxelized surface's terraces and the values' 8-bit rounding.
// Differences are of the normalized value (0..1 over the value window) per
// millimetre, so anisotropic spacing gives the physical gradient direction.
// It is stored in an RGBA8_SNORM texel:
// xyz = unit direction (toward increasing value), w = magnitude in [0, 1]
// where 1 means a change of half the window per voxel step or more.
#ifndef CUTAWAY_GRADIENT_H
#define CUTAWAY_GRADIENT_H

// The gradient bake's set 0 and specialization constant (bake/gradient_bake.cpp).
#define CW_GRADIENT_BIND_VALUES 0     // sampler3D: the values
#define CW_GRADIENT_BIND_OUT 1        // rgba8_snorm storage image: the gradients
#define CW_GRADIENT_BIND_VALUES_R8 2  // the values as r8 storage (CW_STORAGE_PATHS)
#define CW_GRADIENT_BIND_VALUES_R16 3 // the values as r16 storage (CW_STORAGE_PATHS)
#define CW_GRADIENT_SPEC_STORAGE_FETCH 0

#include "shared/glsl_cpp.h"

CW_NAMESPACE_BEGIN

struct GradientParams {
    ivec3 dims;           // voxels
    float magnitudeScale; // smallest spacing (mm) * 2: turns 1/mm into "per half-window per voxel"
    vec3 halfInvSpacing;  // 1 / (2 * spacing), 1/mm
    int bricked;          // 1: texels in the bricked layout (gradientBrickTexel), 0: the grid's
};

// The bricked layout, for devices whose shaders load and filter the texels
// themselves (CPU devices: bake::gradientLayoutFor). Each run of 16 texels
// (64 bytes, one cache line) holds a 4x4 patch of the grid in x and y, the
// patches of a band of 4 rows follow each other along x, and the bands of 4
// slices in z follow each other: a trilinear sample's 8 texels lie in about
// 3 cache lines instead of 4 or more, and a ray's next samples mostly in the
// same ones. The texel of voxel v (v >= 0), in an image of
// gradientBrickExtent(dims).
CW_FUNC ivec3 gradientBrickTexel(ivec3 v) {
    return ivec3((v.x & 3) + 4 * (v.y & 3) + 16 * (v.x >> 2), (v.z & 3) + 4 * (v.y >> 2), v.z >> 2);
}

CW_FUNC ivec3 gradientBrickExtent(ivec3 dims) {
    return ivec3(16 * ((dims.x + 3) / 4), 4 * ((dims.y + 3) / 4), (dims.z + 3) / 4);
}

// The prefilter's taps, [kGradientSideTap kGradientMiddleTap kGradientSideTap]:
// they sum to 1, so a linear ramp's gradient is its slope.
#define kGradientMiddleTap 0.540242f
#define kGradientSideTap 0.229879f

// Weight of a neighbour at transverse offsets (a, b) in {-1, 0, 1}.
CW_FUNC float gradientWeight(int a, int b) {
    return (a == 0 ? kGradientMiddleTap : kGradientSideTap) *
           (b == 0 ? kGradientMiddleTap : kGradientSideTap);
}

// `delta` = the smoothed differences (v[x+1] - v[x-1], ...), neighbours
// clamped to the grid. Returns (direction, magnitude); zero for a flat region,
// told in values per voxel (not per mm), so that a volume of nanometre or
// kilometre voxels is lit as the same volume in millimetres.
CW_FUNC vec4 encodeGradient(vec3 delta, GradientParams p) {
    if (length(delta) < 1e-8f) return vec4(0.0f);
    vec3 g = delta * p.halfInvSpacing;
    float len = length(g);
    return vec4(g / len, min(len * p.magnitudeScale, 1.0f));
}

CW_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(cutaway::shader::GradientParams) == 32);
#endif

#endif

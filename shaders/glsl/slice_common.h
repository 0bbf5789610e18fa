// GLSL only: what every slicing fragment shader shares: the per-sample steps
// (sample_common.h) and the outputs, written by emit().
#ifndef CUTAWAY_SLICE_COMMON_H
#define CUTAWAY_SLICE_COMMON_H

#include "glsl/sample_common.h"

layout(location = 0) out vec4 outColor;
#ifdef CW_WRITE_ID
// What the first visible sample of a pixel was (docs/compositing.md): which
// proxy it came from, its distance from the eye and its label's code.
// Written with the same front-to-back blending as the colour, the first
// write that reaches this attachment saturates its alpha, so later
// fragments add nothing. Codes: 2 the untouched volume, 3 + i operator i
// (0 = nothing visible).
layout(location = 1) out vec4 outId;
#endif
#ifdef CW_WRITE_MATTES
// The mattes: each sample's opacity in its label's channel (matteShares),
// its alpha the sample's, blended as the colour: each channel sums what
// that label's samples add to the pixel.
layout(location = 2) out vec4 outMattes0;
layout(location = 3) out vec4 outMattes1;
#endif

// The fragment's colour `color` from proxy `code`, taken at world point `at`
// (texture coordinate `tc`, whose voxel gives the label).
void emit(vec4 color, float code, vec3 at, vec3 tc) {
    outColor = color;
#ifdef CW_WRITE_ID
    outId = color.a >= CW_ID_MIN_ALPHA ? vec4(code, slabDepth(at), labelCode(tc), 1.0) : vec4(0.0);
#endif
#ifdef CW_WRITE_MATTES
    vec3 first, second;
    matteShares(tc, color.a, first, second);
    outMattes0 = vec4(first, color.a);
    outMattes1 = vec4(second, color.a);
#endif
}

#endif

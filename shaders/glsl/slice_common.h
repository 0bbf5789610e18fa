// GLSL only: what every slicing fragment shader shares: the per-sample steps
// (sample_common.h) and the outputs, written by emit().
#ifndef CUTAWAY_SLICE_COMMON_H
#define CUTAWAY_SLICE_COMMON_H

#include "glsl/sample_common.h"

layout(location = 0) out vec4 outColor;
#ifdef CW_WRITE_ID
// Which proxy the first visible sample of a pixel came from: written with the
// same front-to-back blending as the colour, the first write that reaches this
// attachment saturates its alpha, so later fragments add nothing. Codes:
// 2 the untouched volume, 3 + i operator i (0 = nothing visible).
layout(location = 1) out vec4 outId;
#endif

void emit(vec4 color, float code) {
    outColor = color;
#ifdef CW_WRITE_ID
    outId = color.a >= CW_ID_MIN_ALPHA ? vec4(code, 0.0, 0.0, 1.0) : vec4(0.0);
#endif
}

#endif

// GLSL only: the body of the operator slicing shader (slice_operator.frag.glsl
// and its _id variant). An operator's proxy (paper section 5.1): the fragment
// is a point p' of the deformed space, the front of a slab that reaches the
// next slicing plane; operator_sample.h resolves both ends (Eq. 3, 4) and
// shades the slab.
#include "glsl/operator_sample.h"
#include "glsl/slice_common.h"

layout(location = 0) in vec3 worldPos;
layout(std140, set = 1, binding = CW_BIND_OP_UNIFORMS) uniform Operator {
    OperatorUniforms op;
};
layout(set = 1, binding = CW_BIND_OP_MAP) uniform sampler3D operatorMap;
layout(set = 1, binding = CW_BIND_OP_FEATURE) uniform sampler3D featureTex;
layout(set = 1, binding = CW_BIND_OP_DERIVATIVES) uniform sampler3D operatorDerivatives;

void main() {
    vec3 toEye = toEyeFrom(worldPos);
    float obliquity = obliquityOf(toEye);
    float stepMm = u.viewDir.w * obliquity;
    // The pixel's samples lie this far behind the plane (shared/sampling.h).
    vec3 at = worldPos - toEye * (sampleOffset(gl_FragCoord.xy, u.sampling) * stepMm);
    vec3 step = -toEye * stepMm; // to the slab's back, at the next plane
    Resolved front = resolve(op, operatorMap, featureTex, 0, cwAlignment, at);
    Resolved back = front; // post-classified slices have no back
    if (cwPreintegrated) back = resolve(op, operatorMap, featureTex, 0, cwAlignment, at + step);
    bool moved;
    vec3 source;
    vec4 c =
        refinedOperatorSlab(op, operatorMap, operatorDerivatives, featureTex, 0, cwAlignment, front,
                            back, at, step, viewerOf(toEye, u), obliquity, stepMm, moved, source);
    emit(c, moved ? op.band.y : CW_ID_BACKGROUND, at, source);
}

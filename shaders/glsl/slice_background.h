// GLSL only: the body of the background slicing shader (slice.frag.glsl,
// and slice_id.frag.glsl which also writes the operator-id attachment).
#include "glsl/slice_common.h"

layout(location = 0) in vec3 worldPos;

void main() {
    vec3 toEye = toEyeFrom(worldPos);
    float obliquity = obliquityOf(toEye);
    float stepMm = u.viewDir.w * obliquity;
    // The pixel's samples lie this far behind the plane (shared/sampling.h).
    vec3 at = worldPos - toEye * (sampleOffset(gl_FragCoord.xy, u.sampling) * stepMm);
    vec3 tc = toTexture(at);
    float front = volumeAt(tc);
    float back = front;
    vec3 tcStep = vec3(0.0); // to the slab's back, when pre-integrated
    if (cwPreintegrated) {
        tcStep = toTexture(at - toEye * stepMm) - tc;
        back = volumeAt(tc + tcStep);
    }
    vec4 c = classifySlab(front, back, obliquity, classLayer(tc));
    if (c.a > 0.0) // the lights' half vectors only where something shows
        c = backgroundSlab(c, front, back, tc, tcStep, viewerOf(toEye, u), obliquity);
    emit(c, CW_ID_BACKGROUND, at, tc);
}

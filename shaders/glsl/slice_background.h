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
    vec3 shadeAt = tc; // the slab's middle when pre-integrated
    if (cwPreintegrated) {
        back = volumeAt(toTexture(at - toEye * stepMm));
        shadeAt = toTexture(at - toEye * (0.5 * stepMm));
    }
    emit(backgroundSlab(front, back, tc, shadeAt, toEye, obliquity), CW_ID_BACKGROUND);
}

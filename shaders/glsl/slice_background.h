// GLSL only: the body of the background slicing shader (slice.frag.glsl,
// and slice_id.frag.glsl which also writes the operator-id attachment).
#include "glsl/slice_common.h"

layout(location = 0) in vec3 worldPos;

void main() {
    vec3 tc = toTexture(worldPos);
    vec3 toEye = toEyeFrom(worldPos);
    float obliquity = obliquityOf(toEye);
    float stepMm = u.viewDir.w * obliquity;
    float front = volumeAt(tc);
    float back = front;
    vec3 shadeAt = tc; // the slab's middle when pre-integrated
    if (cwPreintegrated) {
        back = volumeAt(toTexture(worldPos - toEye * stepMm));
        shadeAt = toTexture(worldPos - toEye * (0.5 * stepMm));
    }
    emit(backgroundSlab(front, back, tc, shadeAt, toEye, obliquity), CW_ID_BACKGROUND);
}

// GLSL only: the body of the background slicing shader (slice.frag.glsl,
// and slice_id.frag.glsl which also writes the operator-id attachment).
#include "glsl/slice_common.h"

layout(location = 0) in vec3 worldPos;

void main() {
    vec3 tc = toTexture(worldPos);
    vec3 toEye = toEyeFrom(worldPos);
    float obliquity = obliquityOf(toEye);
    float stepMm = u.viewDir.w * obliquity;
    float front = texture(volumeTex, tc).r;
    float back = front;
    vec3 shadeAt = tc; // the slab's middle when pre-integrated
    if (cwPreintegrated) {
        back = texture(volumeTex, toTexture(worldPos - toEye * stepMm)).r;
        shadeAt = toTexture(worldPos - toEye * (0.5 * stepMm));
    }
    vec4 c = classifySlab(front, back, obliquity, classLayer(tc));
    if (c.a <= 0.0) {
        emit(vec4(0.0), 0.0);
        return;
    }
    emit(shade(c, texture(gradientTex, shadeAt), toEye), CW_ID_BACKGROUND);
}

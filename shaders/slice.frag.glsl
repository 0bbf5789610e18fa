#version 460
// The background proxy: one slab of the untouched volume per fragment. The
// stencil keeps it out of pixels an operator's polygon covers on this slice.
#extension GL_GOOGLE_include_directive : require
#include "glsl/slice_common.h"

layout(location = 0) in vec3 worldPos;
layout(location = 0) out vec4 outColor;

void main() {
    vec3 tc = toTexture(worldPos);
    vec3 toEye = toEyeFrom(worldPos);
    float obliquity = obliquityOf(toEye);
    float stepMm = u.viewDir.w * obliquity;
    float front = texture(volumeTex, tc).r;
    float back = front;
    vec3 shadeAt = tc; // the slab's middle when pre-integrated
    if (u.flags.z > 0.5) {
        back = texture(volumeTex, toTexture(worldPos - toEye * stepMm)).r;
        shadeAt = toTexture(worldPos - toEye * (0.5 * stepMm));
    }
    vec4 c = classifySlab(front, back, obliquity);
    if (c.a <= 0.0) {
        outColor = vec4(0.0);
        return;
    }
    outColor = shade(c, texture(gradientTex, shadeAt), toEye);
}

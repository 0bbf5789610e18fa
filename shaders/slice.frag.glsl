#version 460
// One sample of the volume integral per fragment of a slice: classify through
// the transfer function, correct opacity for the distance between slices
// along this pixel's ray, shade, and emit premultiplied colour for
// front-to-back "under" blending.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame.h"
#include "shared/shading.h"

layout(location = 0) in vec3 worldPos;
layout(location = 0) out vec4 outColor;
layout(std140, set = 0, binding = 0) uniform Frame { FrameUniforms u; };
layout(set = 0, binding = 1) uniform sampler3D volumeTex;
layout(set = 0, binding = 2) uniform sampler3D gradientTex;
layout(set = 0, binding = 3) uniform sampler2D transferTex;

void main() {
    vec3 tc = (u.worldToTexture * vec4(worldPos, 1.0)).xyz;
    float value = texture(volumeTex, tc).r;
    vec4 classified = texture(transferTex, vec2(value * u.valueToTf.x + u.valueToTf.y, 0.5));
    if (classified.a <= 0.0) {
        outColor = vec4(0.0);
        return;
    }
    vec3 toEye = u.eye.w > 0.5 ? normalize(u.eye.xyz - worldPos) : -u.viewDir.xyz;
    // Planes are u.viewDir.w apart along the view direction; an oblique ray
    // (perspective) crosses more material between them.
    float stepMm = u.viewDir.w / max(dot(-toEye, u.viewDir.xyz), 1e-3);
    float alpha = correctOpacity(classified.a, stepMm / u.valueToTf.z);
    vec3 rgb = shadeSample(classified.rgb, texture(gradientTex, tc), toEye, u);
    outColor = vec4(rgb * alpha, alpha);
}

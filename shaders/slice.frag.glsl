#version 460
// One slab of the volume integral per fragment of a slice: classify (from a
// pre-integrated table of the slab's front and back values, or from the 1D
// transfer function at the front), correct opacity for the slab's length along
// this pixel's ray, shade, and emit premultiplied colour for front-to-back
// "under" blending.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame.h"
#include "shared/shading.h"

layout(location = 0) in vec3 worldPos;
layout(location = 0) out vec4 outColor;
layout(std140, set = 0, binding = 0) uniform Frame { FrameUniforms u; };
layout(set = 0, binding = 1) uniform sampler3D volumeTex;
layout(set = 0, binding = 2) uniform sampler3D gradientTex;
layout(set = 0, binding = 3) uniform sampler2D transferTex;

vec3 toTexture(vec3 world) { return (u.worldToTexture * vec4(world, 1.0)).xyz; }

void main() {
    vec3 tc = toTexture(worldPos);
    float front = texture(volumeTex, tc).r;
    vec3 toEye = u.eye.w > 0.5 ? normalize(u.eye.xyz - worldPos) : -u.viewDir.xyz;
    // Planes are u.viewDir.w apart along the view direction; an oblique ray
    // (perspective) crosses 1 / cos more material between them.
    float obliquity = 1.0 / max(dot(-toEye, u.viewDir.xyz), 1e-3);
    float stepMm = u.viewDir.w * obliquity;

    vec4 sampleColor; // premultiplied
    vec3 shadeAt = tc; // where the normal is taken: the slab's middle when it is pre-integrated
    if (u.flags.z > 0.5) {
        shadeAt = toTexture(worldPos - toEye * (0.5 * stepMm));
        float back = texture(volumeTex, toTexture(worldPos - toEye * stepMm)).r;
        vec4 slab = texture(transferTex, vec2(front, back) * u.valueToTf.x + u.valueToTf.y);
        if (slab.a <= 0.0) {
            outColor = vec4(0.0);
            return;
        }
        float alpha = correctOpacity(slab.a, obliquity); // table is for an axial slab
        sampleColor = vec4(slab.rgb * (alpha / slab.a), alpha);
    } else {
        vec4 c = texture(transferTex, vec2(front * u.valueToTf.x + u.valueToTf.y, 0.5));
        if (c.a <= 0.0) {
            outColor = vec4(0.0);
            return;
        }
        float alpha = correctOpacity(c.a, stepMm / u.valueToTf.z);
        sampleColor = vec4(c.rgb * alpha, alpha);
    }
    Lighting light = lightSample(texture(gradientTex, shadeAt), toEye, u);
    outColor = vec4(sampleColor.rgb * light.diffuse + light.specular * sampleColor.a,
                    sampleColor.a);
}

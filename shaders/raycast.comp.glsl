#version 460
// Ray casting (render.method "raycast", docs/performance.md): one invocation
// per pixel marches its ray front to back, taking its samples where the ray
// crosses the slicing planes s_k = (k + 0.5) * spacing, so it samples exactly
// where slicing would and calls the same per-sample code (sample_common.h).
// What it saves over slicing: a slab's back value is the next slab's front
// (one volume fetch per sample instead of two), no rasterization or blending,
// and a ray stops the moment it is opaque. Scenes without operators only.
#extension GL_GOOGLE_include_directive : require
#include "glsl/sample_common.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(set = 0, binding = 5, rgba32f) uniform writeonly image2D target;
layout(push_constant) uniform Ray {
    mat4 clipToWorld;
    vec4 boxLo; // the volume's occupied region (world, mm)
    vec4 boxHi;
} ray;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(target);
    if (pixel.x >= size.x || pixel.y >= size.y) return;
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(size) * 2.0 - 1.0;
    vec4 nearH = ray.clipToWorld * vec4(ndc, 0.0, 1.0);
    vec4 farH = ray.clipToWorld * vec4(ndc, 1.0, 1.0);
    vec3 origin = nearH.xyz / nearH.w; // on the near plane: nothing in front of it is drawn
    vec3 dir = normalize(farH.xyz / farH.w - origin);

    vec3 inv = 1.0 / dir;
    vec3 ta = (ray.boxLo.xyz - origin) * inv, tb = (ray.boxHi.xyz - origin) * inv;
    vec3 tMin = min(ta, tb), tMax = max(ta, tb);
    float tEnter = max(max(tMin.x, tMin.y), max(tMin.z, 0.0));
    float tExit = min(min(tMax.x, tMax.y), tMax.z);
    vec4 sum = vec4(0.0);
    if (tEnter < tExit) {
        vec3 f = u.viewDir.xyz;
        float spacing = u.viewDir.w;
        float fd = dot(f, dir), so = dot(f, origin);
        float first = ceil((so + tEnter * fd) / spacing - 0.5);
        float last = floor((so + tExit * fd) / spacing - 0.5);
        vec3 toEye = -dir;
        float obliquity = obliquityOf(toEye);
        vec3 step = dir * (spacing * obliquity); // from one plane to the next along the ray
        vec3 p = origin + dir * (((first + 0.5) * spacing - so) / fd);
        vec3 tc = toTexture(p);
        vec3 tcStep = toTexture(p + step) - tc;
        float front = textureLod(volumeTex, tc, 0.0).r;
        for (float k = first; k <= last; k += 1.0) {
            float next = textureLod(volumeTex, tc + tcStep, 0.0).r;
            float back = cwPreintegrated ? next : front;
            vec3 shadeAt = cwPreintegrated ? tc + 0.5 * tcStep : tc;
            vec4 c = backgroundSlab(front, back, tc, shadeAt, toEye, obliquity);
            sum += (1.0 - sum.a) * c;
            if (sum.a >= CW_OPAQUE_ALPHA) break;
            tc += tcStep;
            front = next;
        }
    }
    imageStore(target, pixel, sum);
}

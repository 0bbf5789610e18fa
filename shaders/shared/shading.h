// Per-sample math of the volume integral, written once for the shaders and the
// CPU reference: opacity correction and Blinn-Phong shading.
#ifndef CUTAWAY_SHADING_H
#define CUTAWAY_SHADING_H

#include "shared/frame.h"
#include "shared/glsl_cpp.h"

// Whether shading is on and how many directional lights there are: read from
// the frame's flags, unless a shader defines them as specialization constants
// (the slicing shaders do: a software rasterizer runs both sides of a branch).
#ifndef CW_SHADING_ON
#define CW_SHADING_ON(u) ((u).flags.y >= 0.5f)
#endif
#ifndef CW_LIGHT_COUNT
#define CW_LIGHT_COUNT(u) int((u).flags.x)
#endif
// The specular highlight's x^n: pow, unless a shader computes it otherwise
// (the volume shaders do for a whole-number n: sample_common.h).
#ifndef CW_SPECULAR_POWER
#define CW_SPECULAR_POWER(x, n) pow(x, n)
#endif

CW_NAMESPACE_BEGIN

// Opacity of a sample `ratio` reference steps thick, given its opacity for one
// reference step: 1 - (1 - alpha)^ratio. Keeps the image independent of the
// slice spacing (Engel et al., Real-Time Volume Graphics, 2006, eq. 1.12).
CW_FUNC float correctOpacity(float alpha, float ratio) {
    return 1.0f - pow(max(1.0f - alpha, 0.0f), ratio);
}

// Weight of gradient shading for a normalized gradient magnitude in [0, 1]:
// homogeneous regions (tiny gradients, unreliable normals) get no highlight.
CW_FUNC float shadingWeight(float gradientMagnitude) {
    return smoothstep(0.01f, 0.06f, gradientMagnitude);
}

// Where the lights are seen from: the unit vector toward the eye and each
// directional light's Blinn-Phong half vector (the headlight's is toEye
// itself). They depend on the view direction alone, so the ray caster takes
// them once per ray: lavapipe (Mesa 22.3) hoists nothing out of a loop, and
// a normalization per light per sample was a part of every shaded sample.
struct Viewer {
    vec3 toEye;
    vec3 halfway[CW_MAX_LIGHTS];
};

CW_FUNC Viewer viewerOf(vec3 toEye, FrameUniforms u) {
    Viewer v;
    v.toEye = toEye;
    for (int i = 0; i < CW_MAX_LIGHTS; ++i)
        v.halfway[i] = i < CW_LIGHT_COUNT(u) ? normalize(vec3(u.lightDir[i]) + toEye) : vec3(0.0f);
    return v;
}

// Blinn-Phong for one light: nf is the unit normal already turned toward the
// eye (two-sided lighting: a volume has no inside), toLight and halfway unit
// vectors. Returns (diffuse factor, specular factor) scaled by the material.
CW_FUNC vec2 blinnPhong(vec3 nf, vec3 toLight, vec3 halfway, float diffuse, float specular,
                        float shininess) {
    float d = max(dot(nf, toLight), 0.0f);
    float s = d > 0.0f ? CW_SPECULAR_POWER(max(dot(nf, halfway), 0.0f), shininess) : 0.0f;
    return vec2(diffuse * d, specular * s);
}

// Light reaching a sample: Blinn-Phong with an ambient term, a headlight (a
// light at the eye) and up to CW_MAX_LIGHTS directional lights. `gradient` is
// a baked texel (unit direction toward increasing value, magnitude in w); the
// surface normal is its opposite. Where the gradient is too weak to give a
// reliable normal the sample is lit as if it faced the headlight, blended by
// shadingWeight, so homogeneous tissue does not sparkle.
// Shaded premultiplied colour = colour * diffuse + alpha * specular.
struct Lighting {
    vec3 diffuse;
    vec3 specular;
};

// Blinn-Phong with the frame's ambient, headlight and directional lights for
// a surface of unit normal n (either side lit), seen from `v` (viewerOf).
CW_FUNC Lighting lightSurface(vec3 n, Viewer v, FrameUniforms u) {
    vec3 nf = dot(n, v.toEye) < 0.0f ? -n : n;
    Lighting result;
    result.diffuse = vec3(u.material.x);
    result.specular = vec3(0.0f);
    vec2 head = blinnPhong(nf, v.toEye, v.toEye, u.material.y, u.material.z, u.material.w);
    result.diffuse += vec3(u.headlight) * head.x;
    result.specular += vec3(u.headlight) * head.y;
    for (int i = 0; i < CW_LIGHT_COUNT(u); ++i) {
        vec2 l = blinnPhong(nf, vec3(u.lightDir[i]), v.halfway[i], u.material.y, u.material.z,
                            u.material.w);
        result.diffuse += vec3(u.lightColor[i]) * l.x;
        result.specular += vec3(u.lightColor[i]) * l.y;
    }
    return result;
}

CW_FUNC Lighting lightSample(vec4 gradient, Viewer v, FrameUniforms u) {
    Lighting result;
    if (!CW_SHADING_ON(u)) { // shading off: the transfer function's colour as is
        result.diffuse = vec3(1.0f);
        result.specular = vec3(0.0f);
        return result;
    }
    vec3 g = vec3(gradient);
    vec3 n = dot(g, g) > 1e-12f ? normalize(-g) : v.toEye;
    Lighting lit = lightSurface(n, v, u);
    float w = shadingWeight(gradient.w);
    vec3 unlit = vec3(u.material.x) + vec3(u.headlight) * u.material.y;
    result.diffuse = mix(unlit, lit.diffuse, w);
    result.specular = lit.specular * w;
    return result;
}

CW_NAMESPACE_END

#endif

// Uniforms of one slicing pass, shared by the C++ renderer and the shaders.
// std140: only vec4 and mat4 members, so C++ and GLSL agree on every offset
// (checked by static_assert below on the C++ side).
#ifndef CUTAWAY_FRAME_H
#define CUTAWAY_FRAME_H

#include "shared/glsl_cpp.h"

#define CW_MAX_LIGHTS 4

CW_NAMESPACE_BEGIN

struct FrameUniforms {
    mat4 worldToClip;    // world (mm, origin at volume centre) -> Vulkan clip space
    mat4 worldToTexture; // world -> volume texture coordinates, [0,1]^3 over the box
    vec4 eye;            // xyz: eye position (perspective) ; w: 1 perspective, 0 orthographic
    vec4 viewDir;        // xyz: unit forward direction ; w: slice spacing in mm
    vec4 valueToTf;      // x, y: table coordinate = value * x + y ; z: reference step in mm
    vec4 material;       // x ambient, y diffuse, z specular, w shininess
    vec4 headlight;      // rgb: colour * intensity at the eye
    vec4 lightDir[CW_MAX_LIGHTS];   // xyz: unit direction TOWARD the light ; w unused
    vec4 lightColor[CW_MAX_LIGHTS]; // rgb: colour * intensity ; w unused
    vec4 flags;                     // x: number of directional lights ; y: shading on (1) / off (0)
                                    // z: 1 pre-integrated table (2D), 0 post-classification (1D)
                                    // w: 1 classification by label (classTex), 0 one table
    vec4 termination;               // x: early ray termination: a pixel whose composited opacity
                      // reaches this takes no more samples (/render/termination_opacity;
                      // what lies behind could add at most 1 - x to any channel);
                      // y + z * depth (mm along viewDir from the eye): the footprint a
                      // cut's coverage is taken over, in mm (/render/cut_antialias)
    vec4 sampling; // where along the rays the samples lie (shared/sampling.h): x 1 with
                   // /render/jitter, y this pass's offset in spacings, z the seed
};

// The planar depth, in mm, of point `p` in frame `u`: its distance from the
// eye's plane along the view axis, for either projection (what a
// compositor's depth of field reads). The "Z" channel (docs/compositing.md).
CW_FUNC float viewDepth(FrameUniforms u, vec3 p) {
    return dot(p - vec3(u.eye), vec3(u.viewDir));
}

CW_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(cutaway::shader::FrameUniforms) ==
              2 * 64 + 5 * 16 + 2 * CW_MAX_LIGHTS * 16 + 3 * 16);
static_assert(offsetof(cutaway::shader::FrameUniforms, worldToTexture) == 64);
static_assert(offsetof(cutaway::shader::FrameUniforms, eye) == 128);
static_assert(offsetof(cutaway::shader::FrameUniforms, headlight) == 192);
static_assert(offsetof(cutaway::shader::FrameUniforms, lightDir) == 208);
static_assert(offsetof(cutaway::shader::FrameUniforms, lightColor) == 208 + 16 * CW_MAX_LIGHTS);
static_assert(offsetof(cutaway::shader::FrameUniforms, flags) == 208 + 32 * CW_MAX_LIGHTS);
static_assert(offsetof(cutaway::shader::FrameUniforms, termination) == 224 + 32 * CW_MAX_LIGHTS);
static_assert(offsetof(cutaway::shader::FrameUniforms, sampling) == 240 + 32 * CW_MAX_LIGHTS);
#endif

#endif

// What the slicing pass knows about one operator, shared by C++ and GLSL
// (std140: only vec4 and mat4 members).
#ifndef CUTAWAY_OPERATOR_FRAME_H
#define CUTAWAY_OPERATOR_FRAME_H

#include "shared/glsl_cpp.h"

// The most operators a ray-cast frame takes (glsl/ray_march.h): the frame's
// descriptor set and one per operator stay within the four sets every Vulkan
// device can bind at once, and its 9 + 2 per operator combined image samplers
// within the 16 every device's compute stage takes.
#define CW_RAY_MAX_OPERATORS 3

CW_NAMESPACE_BEGIN

struct OperatorUniforms {
    mat4 worldToLocal; // world (mm) -> the operator's local frame (its box is [-1, 1]^3)
    mat4 localToWorld; // A of Eq. 8
    vec4 mapLo;        // xyz: local corner of the baked map's domain (the deformed box V'_T);
                       // w: how far beyond a cut (units of w) a sample may show part of the
                       // material (operators::cutMarginCap)
    vec4 mapHi;        // xyz: opposite corner; w: one texel of the map, local units
    vec4 band;         // x: D of Eq. 7 in local units (0: no blending); y: id code, 3 + index;
                       // z: the cut face's layer, local units (cutFace); w: a bound on
                       // |grad w|, units of w per mm (operators::cutSlope)
    vec4 align;        // x: CW_ALIGN_* (feature.h); y: tau, z: delta (mm, surface);
                       // w: delta for segment alignment's mask (mm, informational)
    vec4 featureScale; // xyz: 1 / (2 spacing) of the feature field's grid, 1/mm
    vec4 featureTc;    // xyz: volume texture coordinate -> the feature texture's: times xyz,
    vec4 featureTc0;   // plus featureTc0.xyz (segment alignment's texture covers a region)
    vec4 blocks;       // xyz: the map's texels across its domain / the texels per block
                       // (render/skipping/operator_regions.hpp; the ray caster's skipping)
    vec4 cutFace;      // /operators/N/cut_face: rgb its colour, w its mix (0: none)
};

// The operator bakes' set 0 (bake/operator_bake.cpp).
#define CW_OPBAKE_BIND_MAP 0         // the map: rgba16f storage image, sampled by the derivatives
#define CW_OPBAKE_BIND_DERIVATIVES 1 // rgba16f storage image: the map's derivatives

// Baking: the push constants of operator_bake.comp.
struct OperatorBakeParams {
    vec4 a; // OperatorParams, unpacked (push constants cannot hold nested structs portably)
    vec4 b;
    vec4 kind;
    vec4 mapLo;
    vec4 mapHi;
    ivec3 dims;
    float pad0;
};

CW_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(cutaway::shader::OperatorUniforms) == 2 * 64 + 9 * 16);
static_assert(offsetof(cutaway::shader::OperatorUniforms, align) == 176);
static_assert(offsetof(cutaway::shader::OperatorUniforms, mapLo) == 128);
static_assert(offsetof(cutaway::shader::OperatorUniforms, band) == 160);
static_assert(sizeof(cutaway::shader::OperatorBakeParams) == 96);
#endif

#endif

// The descriptor bindings and specialization-constant ids that the renderer's
// passes and their shaders share: one name each, used on both sides, so a
// binding the C++ writes is the one the GLSL reads.
#ifndef CUTAWAY_BINDINGS_H
#define CUTAWAY_BINDINGS_H

// Set 0 of the slicing pass, the meshes and the ray caster: the frame's inputs.
#define CW_BIND_FRAME 0     // uniform FrameUniforms (shared/frame.h)
#define CW_BIND_VALUES 1    // sampler3D: the volume's values, normalized over the window
#define CW_BIND_GRADIENTS 2 // sampler3D: their gradients (shared/gradient.h)
#define CW_BIND_TRANSFER 3  // sampler2DArray: one classification table per layer
#define CW_BIND_CLASSES 4   // usampler3D: each voxel's classification layer
// The CPU-device paths (gpu/device_tuning.hpp): bound only where the shaders
// are built with CW_STORAGE_PATHS.
#define CW_BIND_VALUES_R8 15      // the values as an r8 storage image, or a stand-in
#define CW_BIND_VALUES_R16 16     // the values as an r16 storage image, or a stand-in
#define CW_BIND_GRADIENT_IMAGE 17 // the bricked gradients as a storage image, or a stand-in
// Set 0 of the ray caster only.
#define CW_BIND_RAY_TARGET 5      // rgba32f storage image: the colour
#define CW_BIND_RAY_CELLS 6       // r8ui storage image: the cells' distances (ray_cells.hpp)
#define CW_BIND_RAY_MATTES 7      // rgba32f storage image array, 2 layers: the mattes
#define CW_BIND_RAY_OPERATORS 8   // storage buffer: CW_RAY_MAX_OPERATORS OperatorUniforms
#define CW_BIND_RAY_BLOCKS 9      // r8ui storage images 9, 10, 11: each operator slot's blocks
#define CW_BIND_RAY_ID 12         // rgba32f storage image: the AOVs (code, distance, label)
#define CW_BIND_RAY_VISIBLE 13    // storage buffer: VisibleRuns (shared/visible_runs.h)
#define CW_BIND_RAY_MESH_DEPTH 14 // sampler2D: the meshes' depth

// An operator's set: set 1 of the slicing pass, sets 1 + slot of the ray caster.
#define CW_BIND_OP_UNIFORMS 0      // uniform OperatorUniforms (shared/operator_frame.h)
#define CW_BIND_OP_MAP 1           // sampler3D: the baked map
#define CW_BIND_OP_FEATURE 2       // sampler3D: the feature field, or its region
#define CW_BIND_OP_DERIVATIVES 3   // sampler3D: the map's derivatives
#define CW_BIND_OP_FEATURE_IMAGE 4 // r16f storage image: the field again (CW_STORAGE_PATHS)

// The saturation pass's set 0 (render/slicing/saturation_pass.cpp).
#define CW_BIND_SATURATION_COMPOSITE 0 // sampler2D: the slices' composite so far

// Specialization constants of the slicing and ray-casting shaders
// (render/shader_variant.hpp).
#define CW_SPEC_PREINTEGRATED 0
#define CW_SPEC_BY_LABEL 1
#define CW_SPEC_SHADING 2
#define CW_SPEC_LIGHT_COUNT 3
#define CW_SPEC_ALIGNMENT 4     // slot 0's CW_ALIGN_*
#define CW_SPEC_STORAGE_FETCH 5 // 0 sampled, 1 the r8 image, 2 the r16 one
#define CW_SPEC_OPERATOR_COUNT 6
#define CW_SPEC_ALIGNMENT1 7
#define CW_SPEC_ALIGNMENT2 8
#define CW_SPEC_CENSUS 9
#define CW_SPEC_BRICKED_GRADIENTS 10
#define CW_SPEC_WHOLE_SHININESS 11
#define CW_SPEC_CUBIC 12      // /render/filter "cubic"
#define CW_SPEC_REFINE 13     // /render/refine
#define CW_SPEC_LABEL_AOVS 14 // /output/aovs "label": the first visible sample's label
#define CW_SPEC_MATTES 15     // /output/mattes (the ray caster; slicing: CW_WRITE_MATTES)
#define CW_SPEC_COUNT 16

#ifdef __cplusplus
#include "shared/operator_frame.h"
static_assert(CW_RAY_MAX_OPERATORS == 3 &&
                  CW_BIND_RAY_BLOCKS + CW_RAY_MAX_OPERATORS <= CW_BIND_RAY_ID,
              "one blocks binding per ray caster slot (ray_march.h's blocks0..2), before the ids");
#endif

#endif

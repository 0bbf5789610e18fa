#pragma once
// The graphics pipelines of the slicing pass: world-space triangles in, one
// RGBA float colour out with front-to-back premultiplied blending. Slices
// neither test nor write depth (the attachment is there for the mesh pass).
//
// The stencil composites several operators (paper section 5.1): on slice k
// (reference ref(k), set dynamically) an operator's polygon writes ref(k); the
// background polygon is drawn only where the stencil is not ref(k), so no
// region is drawn twice and no slice needs its own clear. An operator's whole
// box is marked by a stencil-only polygon, and its shader runs only on the
// parts of the box where something can show (render/skipping/operator_regions.hpp).
#include "gpu/context.hpp"
#include "gpu/handle.hpp"
#include "render/shader_variant.hpp"

#include <vulkan/vulkan.h>

namespace cutaway::render {

/// What a slice polygon is, which picks its pipeline.
enum class SliceProxy {
    Background,     ///< slice.frag; stencil test != ref, no write
    Operator,       ///< slice_operator.frag; stencil always passes, writes ref
    OperatorStencil ///< no fragment shader, no colour: writes ref over an operator's whole box
};

/// The colour attachments of a frame of `variant`, all of the colour
/// target's format: the colour; with AOVs the id target (proxy code,
/// distance, label code; shaders/glsl/slice_common.h); with mattes two
/// matte targets.
inline std::size_t aovTargetCount(const ShaderVariant& variant) {
    return variant.withAovs ? (variant.mattes ? 4 : 2) : 1;
}

/// The pipeline of `proxy`'s polygons for a frame of `variant`.
gpu::PipelineHandle createSlicePipeline(const gpu::Context& ctx, VkPipelineLayout layout,
                                        const ShaderVariant& variant, SliceProxy proxy);

} // namespace cutaway::render

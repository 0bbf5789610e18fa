#pragma once
// The graphics pipeline of the slicing pass: world-space triangles in, one
// RGBA float colour out with front-to-back premultiplied blending. A
// depth-stencil attachment is declared (for the mesh pass and the per-slice
// operator stencil) but slices neither test nor write depth yet.
#include "gpu/context.hpp"
#include "gpu/handle.hpp"

#include <vulkan/vulkan.h>

namespace cutaway::render {

gpu::PipelineHandle createSlicePipeline(const gpu::Context& ctx, VkPipelineLayout layout);

} // namespace cutaway::render

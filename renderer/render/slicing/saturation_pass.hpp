#pragma once
// Early ray termination for slicing. Slices are composited front to back, so
// once a pixel's alpha reaches the scene's termination opacity
// (/render/termination_opacity) what lies behind hardly shows. Every few
// slices the slicing pass pauses and this pass writes depth 0 into those
// pixels; the slices behind then fail the early depth test and are never
// shaded. Slices keep their LEQUAL depth test against the meshes' depth, so
// one depth buffer carries both.
#include "gpu/context.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/resources.hpp"

namespace cutaway::render {

class SaturationPass {
public:
    SaturationPass(const gpu::Context& ctx, VkSampler nearest);

    /// A descriptor set that reads `color` (kept until the frame is done).
    gpu::DescriptorSet bind(const gpu::Image& color) const;

    /// Outside rendering, between two chunks of slices: `color` is in
    /// COLOR_ATTACHMENT_OPTIMAL before and after, `depthStencil` in
    /// DEPTH_STENCIL_ATTACHMENT_OPTIMAL; its stencil is kept. Marks the
    /// pixels whose alpha is at least `opaqueAlpha`.
    void record(VkCommandBuffer cmd, VkDescriptorSet set, const gpu::Image& color,
                const gpu::Image& depthStencil, float opaqueAlpha) const;

private:
    const gpu::Context& m_ctx;
    VkSampler m_nearest;
    gpu::DescriptorSetLayoutHandle m_setLayout;
    gpu::PipelineLayoutHandle m_layout;
    gpu::PipelineHandle m_pipeline;
};

} // namespace cutaway::render

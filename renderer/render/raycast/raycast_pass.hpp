#pragma once
// The frame by ray casting (render.method "raycast"): the meshes first, with
// a depth the rays can sample, then the Raycaster's compute pass over the
// volume and the operators; its targets are storage images of its own.
#include "gpu/handle.hpp"
#include "gpu/resources.hpp"
#include "render/raycast/raycaster.hpp"
#include "render/render_pass.hpp"

namespace cutaway::render {

class RaycastPass final : public RenderPass {
public:
    /// `operatorLayout`: an operator's set (OperatorStack::setLayout);
    /// `tuning`: whether the shaders take the storage paths and yield lanes.
    RaycastPass(const PassResources& shared, VkDescriptorSetLayout operatorLayout,
                const gpu::DeviceTuning& tuning);
    Image render(const Frame& frame, FrameStats& stats) override;

private:
    void ensureTargets(glm::uvec2 size, bool withMeshes, bool withMattes);
    /// The meshes into Frame::meshes and the rays' depth, copied out.
    void recordMeshes(VkCommandBuffer cmd, const Frame& frame, VkDescriptorSet frameSet);
    Image readBack(const Frame& frame) const;

    PassResources m_shared;
    Raycaster m_raycaster;
    glm::uvec2 m_targetSize{0, 0};
    gpu::Image m_target; ///< RGBA32F storage image
    gpu::Buffer m_readback;
    gpu::Image m_id; ///< RGBA32F storage image: the AOVs (Raycaster::Targets)
    gpu::Buffer m_idReadback;
    gpu::Image m_mattes; ///< RGBA32F, 2 layers; 1x1 while frames have no mattes
    gpu::Buffer m_mattesReadback;
    gpu::Image m_depth; ///< the meshes' depth for the rays, only while frames have meshes
    gpu::ImageViewHandle m_depthView; ///< its depth aspect, sampled
    gpu::Image m_noMeshDepth;         ///< 1x1 R32F of 1: the rays' depth without meshes
};

} // namespace cutaway::render

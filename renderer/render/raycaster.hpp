#pragma once
// The ray-casting integrator (render.method "raycast"; docs/performance.md):
// a compute pass, one invocation per pixel, that samples where the slicing
// planes cross each ray and calls the slicing shaders' per-sample code, so
// its images match slicing's (tests/gpu/raycast_test.cpp). Scenes without
// operators, meshes or the operator-id channel; the scene parser refuses
// the rest.
#include "gpu/context.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/resources.hpp"
#include "render/camera.hpp"
#include "render/slice_pipeline.hpp"

#include <map>

namespace cutaway::render {

class Raycaster {
public:
    Raycaster(const gpu::Context& ctx, VkSampler linear, VkSampler nearest);

    /// What one frame reads (as the slicing pass's set 0) and writes.
    struct Inputs {
        VkBuffer uniforms;
        VkDeviceSize uniformBytes;
        VkImageView values, gradients, transfer, classes;
        VkImageView bricks; ///< R8_UINT, one texel per brick: 1 occupied (occupancy.hpp)
    };
    gpu::DescriptorSet bind(const Inputs& inputs, const gpu::Image& target) const;

    /// Records the pass: `target` (RGBA32F, storage) goes from UNDEFINED to
    /// TRANSFER_SRC_OPTIMAL holding premultiplied colour over nothing.
    /// `occupied` bounds what the rays march through; inside it they step over
    /// the bricks that Inputs::bricks marks empty.
    /// `bricksPerTexture` is how many bricks span the texture along each axis
    /// (the volume's voxels / kBrickVoxels).
    void record(VkCommandBuffer cmd, VkDescriptorSet set, const gpu::Image& target,
                const CameraMatrices& camera, const Box& occupied, glm::vec3 bricksPerTexture,
                const SliceVariant& variant);

private:
    VkPipeline pipelineFor(const SliceVariant& variant);

    const gpu::Context& m_ctx;
    VkSampler m_linear, m_nearest;
    gpu::DescriptorSetLayoutHandle m_setLayout;
    gpu::PipelineLayoutHandle m_layout;
    std::map<SliceVariant, gpu::PipelineHandle> m_pipelines;
};

} // namespace cutaway::render

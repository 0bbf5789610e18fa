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
#include "render/gpu_volume.hpp"
#include "render/occupancy.hpp"
#include "render/slice_pipeline.hpp"

#include <cstdint>
#include <map>
#include <utility>

namespace cutaway::render {

class Raycaster {
public:
    Raycaster(const gpu::Context& ctx, VkSampler linear, VkSampler nearest);

    /// What one frame reads (as the slicing pass's set 0) and writes.
    struct Inputs {
        VkBuffer uniforms;
        VkDeviceSize uniformBytes;
        VkImageView values, gradients, transfer, classes;
        VkImageView transferAlpha; ///< the table's alpha alone (R16F)
    };
    /// Remakes the empty-space cells (ray_cells.hpp) the rays step over when
    /// `occupancySerial` (what `visible` was made for) or the margin for the
    /// frame's slabs (slabMargin) has changed, from the cells' `spans`
    /// (kRayCellVoxels, reaching 1 + the margin; null without the scan on the
    /// host: one cell, the whole box). Call before bind().
    void prepareCells(const GpuVolume& volume, const SpanGrid* spans, const VisibleValues& visible,
                      uint64_t occupancySerial, int marginVoxels);
    gpu::DescriptorSet bind(const Inputs& inputs, const gpu::Image& target) const;

    /// Records the pass: `target` (RGBA32F, storage) goes from UNDEFINED to
    /// TRANSFER_SRC_OPTIMAL holding premultiplied colour over nothing.
    /// The rays march through the occupied cells' bounds and step over the
    /// empty cells.
    void record(VkCommandBuffer cmd, VkDescriptorSet set, const gpu::Image& target,
                const CameraMatrices& camera, const SliceVariant& variant);

private:
    VkPipeline pipelineFor(const SliceVariant& variant);

    const gpu::Context& m_ctx;
    VkSampler m_linear, m_nearest;
    gpu::DescriptorSetLayoutHandle m_setLayout;
    gpu::PipelineLayoutHandle m_layout;
    std::map<SliceVariant, gpu::PipelineHandle> m_pipelines;
    struct Cells {
        gpu::Image distance;                ///< R8_UINT, RayCells::distance
        glm::vec4 perTexture{0.0f};         ///< xyz: cells across the texture; w: the longest slab
                                            ///< they cover, in voxels along each axis
        Box bounds;                         ///< the occupied cells in the world
        std::pair<uint64_t, int> key{0, 0}; ///< occupancy serial, margin
    } m_cells;
};

} // namespace cutaway::render

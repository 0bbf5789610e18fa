#pragma once
// The ray-casting integrator (render.method "raycast"; docs/design/ray-caster.md):
// a compute pass, one invocation per pixel, that samples where the slicing
// planes cross each ray and calls the slicing shaders' per-sample code, so
// its images match slicing's (tests/gpu/raycast_test.cpp,
// raycast_operators_test.cpp). Scenes with up to CW_RAY_MAX_OPERATORS live
// operators (the scene parser refuses more); meshes are drawn before it, and
// their depth ends the rays.
#include "gpu/context.hpp"
#include "gpu/device_tuning.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/resources.hpp"
#include "operators/operator_geometry.hpp"
#include "render/camera.hpp"
#include "render/frame.hpp"
#include "render/gpu_volume.hpp"
#include "render/shader_variant.hpp"
#include "render/skipping/occupancy.hpp"
#include "shared/operator_frame.h"
#include "shared/ray_push.h"

#include <array>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace cutaway::render {

/// Tiles [lo, hi) of the ray caster's 8x8-pixel tiles (empty: lo == hi).
struct TileRect {
    glm::uvec2 lo{0}, hi{0};
    bool empty() const { return lo.x >= hi.x || lo.y >= hi.y; }
};

/// The tiles of an image of `pixels` (the ray caster's, 8x8 each) whose rays
/// may meet the convex hull of `points` (world) through the camera's
/// `viewProj`: the tiles of the points' projected bounds, a pixel wider. All
/// of them when a point lies at or behind the eye.
TileRect tilesCovering(const glm::dmat4& viewProj, const std::vector<glm::dvec3>& points,
                       glm::uvec2 pixels);

class Raycaster {
public:
    /// `operatorSetLayout`: the layout of an operator's descriptor set
    /// (GpuOperator::set, the slicing shader's set 1), visible to compute.
    /// `tuning`: whether the shaders take the storage paths (and so declare
    /// their bindings) and whether lanes yield (the shaders' flavours).
    Raycaster(const gpu::Context& ctx, VkSampler linear, VkSampler nearest,
              VkDescriptorSetLayout operatorSetLayout, const gpu::DeviceTuning& tuning);

    /// The meshes' depth (a depth-only view, DEPTH_STENCIL_READ_ONLY_OPTIMAL),
    /// or any 2D float image of 1 (SHADER_READ_ONLY_OPTIMAL) without meshes.
    struct MeshDepth {
        VkImageView view;
        VkImageLayout layout;
    };
    /// Remakes the empty-space cells (ray_cells.hpp) the rays step over when
    /// `occupancySerial` (what `visible` was made for) or the margin for the
    /// frame's slabs (slabMargin) has changed, from the cells' `spans`
    /// (kRayCellVoxels, reaching 1 + the margin; null without the scan on the
    /// host: one cell, the whole box). Call before bind().
    void prepareCells(const GpuVolume& volume, const SpanGrid* spans, const VisibleValues& visible,
                      uint64_t occupancySerial, int marginVoxels);
    /// An operator of the frame: its descriptor set (map and feature field),
    /// its blocks' chessboard distances (R8_UINT, operator_regions.hpp and
    /// ray_cells.hpp), its uniforms and its CW_ALIGN_* code.
    struct Operator {
        VkDescriptorSet set;
        VkImageView blocks;
        const shader::OperatorUniforms* uniforms;
        int alignment;
        operators::WorldBox box; ///< its deformed box (the map's domain)
    };
    /// What a frame writes, all RGBA32F storage images: premultiplied colour
    /// over nothing; what each pixel's first visible sample was (x its
    /// proxy's code: 0 nothing visible, 2 the untouched volume, 3 + i
    /// operator i; y its distance from the eye; z its label's code; w 1
    /// where there was one); the mattes, two layers (written with
    /// ShaderVariant::mattes only; else a stand-in).
    struct Targets {
        const gpu::Image& color;
        const gpu::Image& id;
        const gpu::Image& mattes;
    };
    /// Set 0 of a frame with these `inputs` and `operators` (see record()).
    gpu::DescriptorSet bind(const FrameInputs& inputs, const MeshDepth& meshDepth,
                            const Targets& targets, const std::vector<Operator>& operators) const;

    /// Records the pass: the targets go from UNDEFINED to
    /// TRANSFER_SRC_OPTIMAL. The rays march through the occupied cells'
    /// bounds, stepping over the empty cells, and through the `operators`'
    /// deformed boxes (at most CW_RAY_MAX_OPERATORS, not overlapping), whose
    /// uniforms it copies into a buffer of set 0 (binding 8): call before
    /// submitting, once per frame, and let the frame finish before the next
    /// record() (RaycastPass submits and waits). With `operatorTiles`, the
    /// shader with operators runs only over the tiles whose rays may meet
    /// their boxes (tilesCovering), the one without over the others; else the
    /// former over the whole image.
    void record(VkCommandBuffer cmd, VkDescriptorSet set, const Targets& targets,
                const CameraMatrices& camera, const ShaderVariant& variant,
                const std::vector<Operator>& operators, bool operatorTiles = true);

private:
    /// The pipeline for `variant` and the operators' alignments (none: the
    /// shader without operators).
    VkPipeline pipelineFor(ShaderVariant variant, const std::vector<int>& alignments);
    /// The operators' shader over `tiles`, with `push` for the whole image.
    void recordOperators(VkCommandBuffer cmd, VkDescriptorSet set, const ShaderVariant& variant,
                         const std::vector<Operator>& operators, const TileRect& tiles,
                         shader::RayPush push);

    const gpu::Context& m_ctx;
    bool m_storageImages;
    VkSampler m_linear, m_nearest;
    gpu::DescriptorSetLayoutHandle m_setLayout;
    gpu::PipelineLayoutHandle m_layout;
    gpu::PipelineLayoutHandle m_operatorLayout; ///< set 0, then one set per operator slot
    std::map<std::pair<ShaderVariant, std::vector<int>>, gpu::PipelineHandle> m_pipelines;
    gpu::Buffer m_operatorUniforms; ///< CW_RAY_MAX_OPERATORS OperatorUniforms, host-mapped
    gpu::Buffer m_visible;          ///< VisibleValues::runs of the cells' classification
    struct Cells {
        gpu::Image distance;                ///< R8_UINT, RayCells::distance
        glm::vec4 perTexture{0.0f};         ///< xyz: cells across the texture; w: the longest slab
                                            ///< they cover, in voxels along each axis
        Box bounds;                         ///< the occupied cells in the world
        std::pair<uint64_t, int> key{0, 0}; ///< occupancy serial, margin
    } m_cells;
};

} // namespace cutaway::render

#pragma once
// Texture-based view-aligned slicing into a float target (paper section 5).
//
// Per frame: the camera is placed, slice polygons are clipped on the CPU and
// drawn front to back in one draw call; each fragment samples the volume,
// classifies, corrects opacity, shades and is composited with premultiplied
// "under" blending (dst += (1 - dst.a) * src). Opaque meshes (tools, glyphs)
// are depth-tested with the slices (see MeshPass). The target is read back and
// the background composited behind everything on the CPU.
#include "gpu/context.hpp"
#include "gpu/handle.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/resources.hpp"
#include "io/image.hpp"
#include "render/gpu_operators.hpp"
#include "render/gpu_volume.hpp"
#include "render/mesh_pass.hpp"
#include "render/occupancy.hpp"
#include "render/operator_regions.hpp"
#include "render/raycaster.hpp"
#include "render/saturation_pass.hpp"
#include "render/slice_pipeline.hpp"
#include "render/slicer.hpp"
#include "scene/scene.hpp"

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <utility>

namespace cutaway::render {

/// Numbers about the last frame, for logs and the benchmark.
struct FrameStats {
    int slices = 0;
    std::size_t vertices = 0;
    int operatorBakes = 0; ///< operator maps baked since the renderer was made
};

class SliceRenderer {
public:
    explicit SliceRenderer(const gpu::Context& ctx);

    /// Renders `scene` (camera, transfer function, lights, render settings) of
    /// the prepared volume. Returns linear premultiplied RGBA, row 0 at the top.
    /// Operators in the scene are baked when their parameters change and
    /// composited with the stencil; overlapping ones are refused (InputError).
    Image render(const Scene& scene, const GpuVolume& volume);

    const FrameStats& lastStats() const { return m_stats; }
    /// Whether operator shaders run only where something can show
    /// (render/operator_regions.hpp; on by default): slicing shades only the
    /// regions, rays step over the empty blocks, and the ray caster's shader
    /// with operators runs only over the tiles of the image their boxes may
    /// cover (Raycaster::record). Off, they run over the whole deformed box
    /// and the whole image, as the tests that compare the two need.
    void setOperatorSkipping(bool on) { m_operatorSkipping = on; }
    /// Whether the shaders load the volume's eight texels and filter them
    /// (sample_common.h's volumeAt) instead of sampling the value texture:
    /// on by default on a CPU device (lavapipe), where that is the faster
    /// way, off on GPUs; only where the device can (DeviceFormats::storageValues).
    void setStorageFetch(bool on) { m_storageFetch = on && m_ctx.formats().storageValues; }
    /// Whether the ray caster's lanes stepping over transparent samples stop
    /// for a pass of shading as soon as one lane of their subgroup waits at
    /// a visible slab (shaders/glsl/ray_march.h, CW_YIELD_LANES): on by default
    /// on a CPU device, which runs a subgroup's lanes in lock-step and pays
    /// for every pass; off on GPUs, where it is not measured; only where
    /// compute shaders have subgroup ballots. The same image either way.
    void setYieldLanes(bool on) { m_yieldLanes = on && m_ctx.computeBallots(); }
    bool yieldLanes() const { return m_yieldLanes; }
    /// The ray caster's census, for performance work (bench --census): on,
    /// a ray-cast frame returns per pixel, instead of colour, how many
    /// samples its ray took of each kind (shaders/glsl/ray_march.h's `census`: r the
    /// untouched volume's values fetched, g its slabs shaded, b operator
    /// points resolved, a operator slabs shaded). Sliced frames ignore it.
    void setCensus(bool on) { m_census = on; }
    /// Feature-field bakes since the last call, one line each (see FeatureFields).
    std::vector<std::string> takeNotes() { return m_operators->features().takeNotes(); }
    /// The feature fields the last frame read (FeatureFields::fieldsInUse).
    std::vector<std::string> fieldsInUse() const { return m_operators->features().fieldsInUse(); }

private:
    /// The frame's targets: the meshes' where it has meshes, slicing's own
    /// (colour, depth-stencil, operator ids) only for a sliced frame.
    void ensureTargets(uint32_t width, uint32_t height, bool withOperatorId, bool withMeshes,
                       bool slicing);
    void ensureVertexCapacity(std::size_t bytes);
    /// Draws slices [begin, end) inside a rendering pass.
    void recordSlices(VkCommandBuffer cmd, const SliceSet& slices, VkDescriptorSet frameSet,
                      SliceVariant frame, std::size_t begin, std::size_t end);
    /// The volume's occupied bricks for this scene's transfer functions
    /// (render/occupancy.hpp), remade when those change.
    /// `marginVoxels`: for the frame's longest slab (slabMargin).
    const BrickOccupancy& occupancyFor(const Scene& scene, const GpuVolume& volume,
                                       int marginVoxels);
    /// What skips operator `index`'s empty space, each part made on first
    /// use and dropped when the operator, its feature field or the
    /// occupancy change.
    struct Regions {
        std::vector<double> key;
        /// Slicing's: the active blocks merged into boxes, of the blocks
        /// where a brick is occupied (CaseOccupancy without the feature
        /// field: finer regions split the box into more polygons, and their
        /// T-junctions leave seams of pixels shaded twice or not at all).
        std::optional<std::vector<operators::LocalBox>> boxes;
        /// The ray caster's: chessboardDistance (R8_UINT) of the blocks where
        /// each case of Eq. 4 can show something (casesFor), exact for rays.
        gpu::Image distance;
    };
    /// Operator `index`'s Regions, emptied when their key changes.
    Regions& regionsFor(std::size_t index, const GpuOperator& op, double reachMm);
    /// Slicing's boxes of operator `index` (Regions::boxes).
    const std::vector<operators::LocalBox>& boxesFor(std::size_t index, const GpuOperator& op,
                                                     double reachMm);
    /// Where each case of Eq. 4 can show something for operator `op`, with
    /// its feature field's ranges where it has one (render/case_occupancy.hpp).
    const CaseOccupancy& casesFor(const GpuOperator& op);
    /// render.method "raycast": the frame by ray casting, over nothing.
    /// `marginVoxels`: for the frame's longest slab (slabMargin).
    /// The chessboard distances of operator `index`'s blocks for the rays
    /// (one active block when operator skipping is off), made on first use.
    VkImageView blocksFor(std::size_t index, const GpuOperator& op, double reachMm);
    /// `reachMm`: the frame's longest slab, for the operators' blocks;
    /// `frameSet`: the slicing pass's set 0, for the meshes drawn first.
    /// Bindings 15 and 16: the values as a storage image in the one of
    /// their format (R8, R16), a stand-in in the other.
    std::array<VkImageView, 2> valueImages(const GpuVolume& volume) const;
    Image renderRaycast(const CameraMatrices& cam, const GpuVolume& volume,
                        const gpu::Image& transfer, const SliceVariant& variant, int marginVoxels,
                        double reachMm, VkDescriptorSet frameSet);
    /// The volume's image over the meshes' (read back after their pass).
    void compositeMeshes(Image& image) const;
    /// The operator_id channel's value for a pixel whose first visible
    /// sample came from the proxy with `code` (CW_ID_BACKGROUND in
    /// shaders/glsl/sample_common.h): -2 nothing, -1 the volume, i operator i.
    static float operatorIdOf(float code, bool covered);
    static void compositeUnder(Image& image, glm::vec4 background);
    /// The pipeline of `variant`, made on first use (a few per scene).
    VkPipeline pipelineFor(const SliceVariant& variant);

    const gpu::Context& m_ctx;
    gpu::SamplerHandle m_sampler;
    gpu::SamplerHandle m_nearest;                       ///< for the integer class texture
    gpu::DescriptorSetLayoutHandle m_setLayout;         ///< set 0: frame
    gpu::DescriptorSetLayoutHandle m_operatorSetLayout; ///< set 1: one operator
    gpu::PipelineLayoutHandle m_layout;
    std::map<SliceVariant, gpu::PipelineHandle> m_pipelines;
    std::unique_ptr<OperatorStack> m_operators;
    std::unique_ptr<MeshPass> m_meshes;
    std::unique_ptr<SaturationPass> m_saturation;
    std::unique_ptr<Raycaster> m_raycaster;
    gpu::Image m_rayTarget; ///< RGBA32F storage image, only while scenes ray-cast
    gpu::Buffer m_rayReadback;
    gpu::Image m_rayId; ///< R32F storage image: each pixel's operator-id code
    gpu::Image
        m_rayDepth; ///< the meshes' depth for the rays, only while ray-cast scenes have meshes
    gpu::ImageViewHandle m_rayDepthView; ///< its depth aspect, sampled
    gpu::Image m_noMeshDepth;            ///< 1x1 R32F of 1: the rays' depth without meshes
    gpu::Buffer m_rayIdReadback;
    std::optional<SpanGrid> m_cellSpans;    ///< the ray caster's cells (null: no host scan)
    std::optional<SpanGrid> m_brickSpans;   ///< the slicing bricks': the cells' unions
    std::vector<double> m_spanKey;          ///< volume, window, margin
    std::optional<VisibleValues> m_visible; ///< what the frame's classification can show
    BrickOccupancy m_occupancy;
    std::vector<Box> m_occupied; ///< m_occupancy.boxes(): the volume's proxies
    std::vector<double> m_occupiedKey;
    uint64_t m_occupancySerial = 0; ///< counts remakes of m_occupancy
    std::vector<Regions> m_regions; ///< per operator
    /// casesFor's, by occupancy serial, field, threshold and alignment: an
    /// operator that moves keeps its feature's cells (up to 4 MB on the frog).
    std::map<std::vector<double>, CaseOccupancy> m_cases;
    bool m_operatorSkipping = true;
    bool m_storageFetch = false;
    bool m_yieldLanes = false;
    bool m_census = false;
    /// The values' storage bindings 15 (R8) and 16 (R16) and their stand-ins.
    bake::ValueStorageBindings m_valueBindings;
    gpu::Image m_noSkipping; ///< the ray caster's blocks when skipping is off: one, active
    /// What each proxy of the frame is: operator `op`'s stencil box or one of
    /// its regions, or (op < 0) a box of the volume's occupied bricks.
    struct ProxyRole {
        int op = -1;
        bool stencil = false;
    };
    std::vector<ProxyRole> m_roles;
    /// Slices between two saturation passes: fewer means earlier termination
    /// and more pauses (each a full-screen pass, ~0.3 ms at 512^2 on lavapipe).
    static constexpr std::size_t kSlicesPerChunk = 16;
    gpu::Buffer m_uniforms;
    gpu::Buffer m_vertices;
    glm::uvec2 m_targetSize{0, 0}; ///< of every target below and the ray caster's
    gpu::Image m_color;
    gpu::Image m_depthStencil;
    gpu::Buffer m_readback;
    gpu::Image m_transfer;             ///< classification table, remade when its inputs change
    std::vector<double> m_transferKey; ///< those inputs (pre-integration costs ~170 ms)
    gpu::Image m_classes;              ///< each voxel's classification layer (R8_UINT)
    std::vector<double> m_classesKey;  ///< the volume and the label lists it came from
    gpu::Image m_meshColor;            ///< the meshes' image, only while scenes have meshes
    gpu::Buffer m_meshReadback;
    gpu::Image m_operatorId; ///< only while scenes ask for output.operator_id
    gpu::Buffer m_operatorIdReadback;
    FrameStats m_stats;
};

} // namespace cutaway::render

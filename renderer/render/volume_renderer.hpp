#pragma once
// The renderer's front: one frame of a scene from its prepared volume.
//
// Per frame it brings the device state up to date with the scene (the
// operators' baked maps, the classification tables, the empty-space
// structures, the meshes), places the camera and the slabs (frame.hpp),
// fixes the shader variant, and hands the frame to the pass the scene's
// render.method names: slicing (the paper's method, the default;
// slicing/slicing_pass.hpp) or ray casting (raycast/raycast_pass.hpp). The
// pass returns the volume's image over nothing; the front composites the
// meshes' image and the background behind it.
//
// What differs between devices (storage images on CPU implementations,
// yielding lanes) is decided once, by the gpu::DeviceTuning it is made with.
#include "bake/volume_upload.hpp"
#include "gpu/context.hpp"
#include "gpu/device_tuning.hpp"
#include "gpu/handle.hpp"
#include "gpu/resources.hpp"
#include "io/image.hpp"
#include "render/classify/classification_upload.hpp"
#include "render/gpu_operators.hpp"
#include "render/gpu_volume.hpp"
#include "render/mesh_pass.hpp"
#include "render/render_pass.hpp"
#include "render/skipping/empty_space.hpp"
#include "scene/scene.hpp"
#include "shared/frame.h"

#include <memory>
#include <string>
#include <vector>

namespace cutaway::render {

class VolumeRenderer {
public:
    /// With the device's tuning (Context::tuning).
    explicit VolumeRenderer(const gpu::Context& ctx);
    /// With `tuning` instead, less what the device cannot run (tests: the
    /// GPU profile on lavapipe, each CPU path on and off).
    VolumeRenderer(const gpu::Context& ctx, const gpu::DeviceTuning& tuning);
    ~VolumeRenderer();

    /// Renders `scene` (camera, transfer function, lights, render settings) of
    /// the prepared volume. Returns linear premultiplied RGBA, row 0 at the top.
    /// Operators in the scene are baked when their parameters change and
    /// composited with the stencil; overlapping ones are refused (InputError).
    /// The volume must be prepared for this renderer's tuning
    /// (prepareVolume with a GradientBaker of the same tuning).
    Image render(const Scene& scene, const GpuVolume& volume);

    const FrameStats& lastStats() const { return m_stats; }
    const gpu::DeviceTuning& tuning() const { return m_tuning; }
    /// Whether operator shaders run only where something can show
    /// (skipping/empty_space.hpp; on by default). Off, they run over the
    /// whole deformed box and the whole image, as the tests that compare the
    /// two need.
    void setOperatorSkipping(bool on) { m_emptySpace->setOperatorSkipping(on); }
    /// The ray caster's census, for performance work (bench --census): on,
    /// a ray-cast frame returns per pixel, instead of colour, how many
    /// samples its ray took of each kind (shaders/glsl/ray_march.h's
    /// `census`: r the untouched volume's values fetched, g its slabs shaded,
    /// b operator points resolved, a operator slabs shaded). Sliced frames
    /// ignore it.
    void setCensus(bool on) { m_census = on; }
    /// Feature-field bakes since the last call, one line each (see FeatureFields).
    std::vector<std::string> takeNotes() { return m_operators->features().takeNotes(); }
    /// The feature fields the last frame read, one line each (FeatureFields).
    std::vector<std::string> fieldsInUse() const { return m_operators->features().fieldsInUse(); }
    /// Stand-in storage images made so far (bake::ValueStorageBindings): none
    /// where the tuning takes no storage paths.
    int storageStandIns() const { return m_storage.standIns(); }

private:
    /// What `scene` fixes in the shaders for `volume`.
    ShaderVariant variantFor(const Scene& scene, const GpuVolume& volume) const;
    /// The frame's set-0 inputs (frame.hpp).
    FrameInputs inputsFor(const GpuVolume& volume);
    /// The meshes' colour target and readback, while frames have meshes.
    void ensureMeshTargets(glm::uvec2 size, bool withMeshes);
    /// The pass `scene` asks for.
    RenderPass& passFor(const Scene& scene);
    /// `frame` by `pass`, once per /render/samples with each pass's offset
    /// written into `uniforms`, averaged.
    Image renderPasses(RenderPass& pass, const Frame& frame, shader::FrameUniforms& uniforms);

    const gpu::Context& m_ctx;
    gpu::DeviceTuning m_tuning;
    gpu::SamplerHandle m_linear;
    gpu::SamplerHandle m_nearest;                 ///< for the integer class texture
    gpu::DescriptorSetLayoutHandle m_frameLayout; ///< slicing's and the meshes' set 0
    std::unique_ptr<OperatorStack> m_operators;
    std::unique_ptr<MeshPass> m_meshes;
    std::unique_ptr<EmptySpace> m_emptySpace;
    ClassificationTables m_classification;
    bake::ValueStorageBindings m_storage;
    gpu::Buffer m_uniforms;
    glm::uvec2 m_meshSize{0, 0};
    MeshTargets m_meshTargets;             ///< only while frames have meshes
    std::unique_ptr<RenderPass> m_slicing; ///< made on first use, as the ray caster
    std::unique_ptr<RenderPass> m_raycast;
    bool m_census = false;
    FrameStats m_stats;
};

} // namespace cutaway::render

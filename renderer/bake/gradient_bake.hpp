#pragma once
// The gradient bake: one compute dispatch over the volume texture writes an
// RGBA8_SNORM texture of (unit gradient direction, magnitude); see
// shaders/shared/gradient.h for the encoding.
#include "bake/volume_upload.hpp"
#include "gpu/context.hpp"
#include "gpu/device_tuning.hpp"
#include "gpu/handle.hpp"
#include "gpu/resources.hpp"

#include <glm/glm.hpp>
#include <mutex>

namespace cutaway::bake {

/// How the gradient texels lie in their image. Linear: on the volume's grid,
/// for the device's sampler. Bricked: gradientBrickTexel's layout, which the
/// shaders load and filter themselves (sample_common.h's gradientAt); on a
/// CPU device the 8 texels of a sample then share cache lines.
enum class GradientLayout { Linear, Bricked };

/// Bricked where `tuning` asks (CPU devices) and the bricked image fits the
/// device's 3D image size; linear on GPUs, whose samplers filter for free.
GradientLayout gradientLayoutFor(const gpu::Context& ctx, const gpu::DeviceTuning& tuning,
                                 glm::ivec3 dims);

class GradientBaker {
public:
    /// `tuning` (the device's by default) decides whether the bake reads the
    /// values as a storage image (an inline load on lavapipe) instead of
    /// sampling them (the texels are the same either way), how the
    /// gradients lie and the layout they rest in.
    explicit GradientBaker(const gpu::Context& ctx);
    GradientBaker(const gpu::Context& ctx, const gpu::DeviceTuning& tuning);

    /// `values` is the uploaded volume (bake::uploadVolume). The result rests
    /// in GENERAL when bricked or where the tuning takes storage paths (the
    /// shaders may load it as a storage image), else in
    /// SHADER_READ_ONLY_OPTIMAL (Image::layout), for fragment and compute
    /// shaders.
    gpu::Image bake(const gpu::Image& values, glm::dvec3 spacing, GradientLayout layout) const;
    /// The same, in gradientLayoutFor's layout.
    gpu::Image bake(const gpu::Image& values, glm::dvec3 spacing) const;

    /// The paths it takes (supported by the device): what a volume it bakes
    /// for is prepared for (render::prepareVolume).
    const gpu::DeviceTuning& tuning() const { return m_tuning; }
    bool storageFetch() const { return m_tuning.storageValues; }

private:
    /// The pipeline for cwStorageFetch `fetch` (0 sampled, 1 R8, 2 R16),
    /// made on first use (a device uses one or two of the three).
    VkPipeline pipelineFor(int fetch) const;

    const gpu::Context& m_ctx;
    gpu::DeviceTuning m_tuning;
    gpu::DescriptorSetLayoutHandle m_setLayout;
    gpu::PipelineLayoutHandle m_layout;
    gpu::ShaderModuleHandle m_module;
    mutable std::mutex m_pipelinesMutex; ///< bake() may be called from several threads
    mutable gpu::PipelineHandle m_pipelines[3];
    gpu::SamplerHandle m_sampler;
    mutable ValueStorageBindings m_valueBindings; ///< its stand-ins are made on first use
};

} // namespace cutaway::bake

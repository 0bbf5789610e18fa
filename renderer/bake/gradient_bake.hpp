#pragma once
// The gradient bake: one compute dispatch over the volume texture writes an
// RGBA8_SNORM texture of (unit gradient direction, magnitude); see
// shaders/shared/gradient.h for the encoding.
#include "bake/volume_upload.hpp"
#include "gpu/context.hpp"
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

/// Bricked on CPU devices (lavapipe) where the bricked image fits the
/// device's 3D image size; linear on GPUs, whose samplers filter for free.
GradientLayout gradientLayoutFor(const gpu::Context& ctx, glm::ivec3 dims);

/// The layout the baked gradients are left in: GENERAL, since the bricked
/// ones are read as a storage image (like the values, kValuesLayout).
inline constexpr VkImageLayout kGradientsLayout = VK_IMAGE_LAYOUT_GENERAL;

class GradientBaker {
public:
    explicit GradientBaker(const gpu::Context& ctx);

    /// `values` is the uploaded volume (in bake::kValuesLayout). The result
    /// is left in kGradientsLayout for fragment and compute shaders.
    gpu::Image bake(const gpu::Image& values, glm::dvec3 spacing, GradientLayout layout) const;
    /// The same, in gradientLayoutFor's layout.
    gpu::Image bake(const gpu::Image& values, glm::dvec3 spacing) const;

    /// Whether the bake reads the values as a storage image (an inline load
    /// on lavapipe) instead of sampling them: on by default on CPU devices,
    /// off on GPUs; only where the device can (DeviceFormats::storageValues).
    /// The texels are the same either way.
    void setStorageFetch(bool on) { m_storageFetch = on && m_ctx.formats().storageValues; }
    bool storageFetch() const { return m_storageFetch; }

private:
    /// The pipeline for cwStorageFetch `fetch` (0 sampled, 1 R8, 2 R16),
    /// made on first use (a device uses one or two of the three).
    VkPipeline pipelineFor(int fetch) const;

    const gpu::Context& m_ctx;
    gpu::DescriptorSetLayoutHandle m_setLayout;
    gpu::PipelineLayoutHandle m_layout;
    gpu::ShaderModuleHandle m_module;
    mutable std::mutex m_pipelinesMutex; ///< bake() may be called from several threads
    mutable gpu::PipelineHandle m_pipelines[3];
    gpu::SamplerHandle m_sampler;
    ValueStorageBindings m_valueBindings;
    bool m_storageFetch = false;
};

} // namespace cutaway::bake

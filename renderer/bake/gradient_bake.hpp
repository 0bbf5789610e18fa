#pragma once
// The gradient bake: one compute dispatch over the volume texture writes an
// RGBA8_SNORM texture of (unit gradient direction, magnitude); see
// shaders/shared/gradient.h for the encoding.
#include "gpu/context.hpp"
#include "gpu/handle.hpp"
#include "gpu/resources.hpp"

#include <glm/glm.hpp>

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

private:
    const gpu::Context& m_ctx;
    gpu::DescriptorSetLayoutHandle m_setLayout;
    gpu::PipelineLayoutHandle m_layout;
    gpu::PipelineHandle m_pipeline;
    gpu::SamplerHandle m_sampler;
};

} // namespace cutaway::bake

#pragma once
// The gradient bake: one compute dispatch over the volume texture writes an
// RGBA8_SNORM texture of (unit gradient direction, magnitude); see
// shaders/shared/gradient.h for the encoding.
#include "gpu/context.hpp"
#include "gpu/handle.hpp"
#include "gpu/resources.hpp"

#include <glm/glm.hpp>

namespace cutaway::bake {

class GradientBaker {
public:
    explicit GradientBaker(const gpu::Context& ctx);

    /// `values` is the uploaded volume (in bake::kValuesLayout). The result
    /// is left SHADER_READ_ONLY_OPTIMAL for fragment and compute shaders.
    gpu::Image bake(const gpu::Image& values, glm::dvec3 spacing) const;

private:
    const gpu::Context& m_ctx;
    gpu::DescriptorSetLayoutHandle m_setLayout;
    gpu::PipelineLayoutHandle m_layout;
    gpu::PipelineHandle m_pipeline;
    gpu::SamplerHandle m_sampler;
};

} // namespace cutaway::bake

#pragma once
// Bakes an operator's continuous backward map into an RGBA16F 3D texture over
// the local box [lo, hi] (its deformed box): xyz = pre-image - q, w = signed
// distance to the cut. Done when the operator's parameters change.
#include "gpu/context.hpp"
#include "gpu/handle.hpp"
#include "gpu/resources.hpp"
#include "shared/operators.h"

#include <glm/glm.hpp>

namespace cutaway::bake {

class OperatorBaker {
public:
    explicit OperatorBaker(const gpu::Context& ctx);

    /// The result is left SHADER_READ_ONLY_OPTIMAL for fragment shaders and copies.
    gpu::Image bake(const shader::OperatorParams& params, glm::vec3 lo, glm::vec3 hi,
                    glm::ivec3 dims) const;

private:
    const gpu::Context& m_ctx;
    gpu::DescriptorSetLayoutHandle m_setLayout;
    gpu::PipelineLayoutHandle m_layout;
    gpu::PipelineHandle m_pipeline;
};

} // namespace cutaway::bake

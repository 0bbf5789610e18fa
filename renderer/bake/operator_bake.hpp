#pragma once
// Bakes an operator's continuous backward map into an RGBA16F 3D texture over
// the local box [lo, hi] (its deformed box): xyz = pre-image - q, w = signed
// distance to the cut; and the map's derivatives along the box's three axes,
// for the Jacobian of Eq. 5 and the cut's normal (Eq. 7). Done when the
// operator's parameters change.
#include "gpu/context.hpp"
#include "gpu/handle.hpp"
#include "gpu/resources.hpp"
#include "shared/operators.h"

#include <glm/glm.hpp>

namespace cutaway::bake {

struct BakedMap {
    /// RGBA16F, dims: the map (displacement, w).
    gpu::Image map;
    /// RGBA16F, 3 h.x x h.y x h.z for h = derivativeDims(dims): section i
    /// (texels x + i h.x) holds the map's central differences along local
    /// axis i, per local unit, at half the map's resolution
    /// (shaders/operator_derivative.comp.glsl). Side by side along x, a
    /// texel's three lie in one row: sections along z, a map apart, made the
    /// fetches of the ray caster slower.
    gpu::Image derivatives;
};

/// The grid of a map's derivatives: half the map's, rounded up.
inline glm::ivec3 derivativeDims(glm::ivec3 mapDims) {
    return (mapDims + 1) / 2;
}

class OperatorBaker {
public:
    explicit OperatorBaker(const gpu::Context& ctx);

    /// Both results are left SHADER_READ_ONLY_OPTIMAL for the shaders and copies.
    BakedMap bake(const shader::OperatorParams& params, glm::vec3 lo, glm::vec3 hi,
                  glm::ivec3 dims) const;

private:
    const gpu::Context& m_ctx;
    gpu::DescriptorSetLayoutHandle m_setLayout;
    gpu::PipelineLayoutHandle m_layout;
    gpu::PipelineHandle m_pipeline;
    gpu::DescriptorSetLayoutHandle m_derivativeSetLayout;
    gpu::PipelineLayoutHandle m_derivativeLayout;
    gpu::PipelineHandle m_derivativePipeline;
    gpu::SamplerHandle m_nearest; ///< the derivatives' pass reads the map with texelFetch
};

} // namespace cutaway::bake

#pragma once
// The range of a feature field (surface alignment's DT, segment alignment's M)
// over each cell of the ray caster's grid, for empty-space skipping in an
// operator's box (render/skipping/case_occupancy.hpp): where a field's range stays on
// one side of the mask's threshold, only one case of Eq. 4 can occur there.
// One signed byte for each end (2 bytes a cell of 2^3 voxels: 1/8 of the
// field's own size), computed by feature_ranges.comp and read back once per
// field.
#include "gpu/context.hpp"
#include "gpu/handle.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/resources.hpp"

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace cutaway::bake {

struct FieldRanges {
    glm::ivec3 cells{0};
    int cellVoxels = 1;
    float scale = 1.0f;       ///< steps per unit of the field
    std::vector<int8_t> lohi; ///< per cell, x fastest: lo, hi in steps (encodeFieldRange)

    /// Whether the field can reach `threshold` or more in cell i (false
    /// where it certainly stays below).
    bool mayReach(std::size_t i, double threshold) const;
    /// Whether the field can be below `threshold` in cell i.
    bool mayBeBelow(std::size_t i, double threshold) const;
    /// Whether the byte steps can tell `threshold` apart: within the range
    /// they hold, with a step to spare for the rounding at either end.
    bool resolves(double threshold) const;
};

/// The ranges of `field` (dims voxels, x fastest) on the CPU, as the shader
/// computes them.
FieldRanges fieldRangesCpu(const std::vector<float>& field, glm::ivec3 dims, int cellVoxels,
                           float scale);

class FieldRangeBaker {
public:
    explicit FieldRangeBaker(const gpu::Context& ctx);

    /// The ranges of `field` (R16F, 3D, in kFeatureLayout) over cells of
    /// `cellVoxels`^3 voxels (the last ones partial).
    FieldRanges ranges(const gpu::Image& field, int cellVoxels, float scale) const;

private:
    const gpu::Context& m_ctx;
    gpu::DescriptorSetLayoutHandle m_setLayout;
    gpu::PipelineLayoutHandle m_layout;
    gpu::PipelineHandle m_pipeline;
};

} // namespace cutaway::bake

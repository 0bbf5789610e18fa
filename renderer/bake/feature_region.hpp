#pragma once
// Segment alignment's feature texture over one operator's region: the voxels
// the operator's baked map can read (its deformed box, which holds both p'
// and p0 of Eq. 3), with a margin. An RG16F texture: r = M as the segment
// mask stores it, g = the value material that moves with the operator reads
// there (movedValue in shaders/shared/feature_bake.h, its CPU twin in
// operators/moved_value.hpp: the segment's voxels next to moving material
// take their outside neighbours' mean, so a flap lifted off a thin segment
// such as the skull takes none of its value along).
// It replaces the whole-grid mask in the operator's descriptor set; the mask
// itself stays cached in FeatureFields, so moving the operator makes only a
// new region (4 bytes per voxel of the region).
#include "gpu/context.hpp"
#include "gpu/handle.hpp"
#include "gpu/resources.hpp"

#include <glm/glm.hpp>

namespace cutaway::bake {

/// Voxels [lo, lo + size) of a grid.
struct VoxelRegion {
    glm::ivec3 lo{0};
    glm::ivec3 size{1};
    bool operator==(const VoxelRegion&) const = default;
};

/// The voxels of a grid (`dims` voxels of `spacing`, its low corner at
/// `gridLo`, mm) that a trilinear sample anywhere in the world box [boxLo,
/// boxHi] reads, with `margin` voxels more on every side; clamped to the
/// grid, at least one voxel.
VoxelRegion regionCovering(glm::ivec3 dims, glm::dvec3 spacing, glm::dvec3 gridLo, glm::dvec3 boxLo,
                           glm::dvec3 boxHi, int margin = 2);

class FeatureRegionBaker {
public:
    explicit FeatureRegionBaker(const gpu::Context& ctx);

    /// `values`: the uploaded volume; `mask`: its segment mask
    /// (FeatureBaker::segmentMask, kFeatureLayout), on the same grid. Result: RG16F over
    /// `region`, SHADER_READ_ONLY_OPTIMAL for fragment and compute shaders.
    gpu::Image bake(const gpu::Image& values, const gpu::Image& mask, VoxelRegion region) const;

private:
    const gpu::Context& m_ctx;
    gpu::DescriptorSetLayoutHandle m_setLayout;
    gpu::PipelineLayoutHandle m_layout;
    gpu::PipelineHandle m_pipeline;
    gpu::SamplerHandle m_sampler;
};

} // namespace cutaway::bake

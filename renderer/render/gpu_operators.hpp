#pragma once
// The operators of the frame on the device: each one's baked map (remade only
// when its parameters or resolution change; moving an operator only updates
// its uniforms), its place in the world, and the descriptor set the operator
// slicing shader reads (set 1: uniforms, map).
#include "bake/feature_region.hpp"
#include "bake/operator_bake.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/resources.hpp"
#include "operators/operator_geometry.hpp"
#include "render/feature_fields.hpp"
#include "render/gpu_volume.hpp"
#include "scene/scene.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace cutaway::render {

/// CW_ALIGN_* of shaders/shared/feature.h for an alignment mode.
int alignmentCode(AlignmentMode mode);

struct GpuOperator {
    OperatorSpec spec;
    operators::WorldBox box; ///< the deformed box in the world: the operator's proxy
    gpu::Image map;
    gpu::Image derivatives; ///< the map's, along its three axes, at half its resolution (BakedMap)
    /// Segment alignment: the feature texture over the operator's region
    /// (bake/feature_region.hpp), made from the field `regionField` (its id in
    /// FeatureFields) over `regionVoxels`; empty otherwise.
    gpu::Image region;
    bake::VoxelRegion regionVoxels;
    std::uint64_t regionField = 0;
    /// The id of the feature field it reads (FeatureFields::fieldFor; 0 for axis alignment).
    std::uint64_t fieldId = 0;
    gpu::Buffer uniforms;
    gpu::DescriptorSet set;
};

class OperatorStack {
public:
    /// `storageImages`: the shaders that read the sets take the storage paths
    /// (gpu::DeviceTuning::storageImages), so each set also holds the feature
    /// field as a storage image.
    OperatorStack(const gpu::Context& ctx, VkSampler sampler, bool storageImages);
    /// The layout of each operator's set (GpuOperator::set): set 1 of the
    /// slicing shaders, sets 1 + slot of the ray caster's.
    VkDescriptorSetLayout setLayout() const { return m_setLayout.get(); }

    /// Makes the device state match `specs` on `volume`: refuses overlapping
    /// operators (InputError naming both), bakes what changed.
    void update(const std::vector<OperatorSpec>& specs, const GpuVolume& volume);

    const std::vector<std::unique_ptr<GpuOperator>>& operators() const { return m_operators; }
    int bakes() const { return m_bakes; } ///< maps baked so far, for tests
    FeatureFields& features() { return m_features; }
    const FeatureFields& features() const { return m_features; }

private:
    const gpu::Context& m_ctx;
    bool m_storageImages;
    gpu::DescriptorSetLayoutHandle m_setLayout;
    VkSampler m_sampler;
    bake::OperatorBaker m_baker;
    bake::FeatureRegionBaker m_regionBaker;
    FeatureFields m_features;
    std::vector<std::unique_ptr<GpuOperator>> m_operators;
    int m_bakes = 0;
};

} // namespace cutaway::render

#pragma once
// The compute bakes of feature alignment (paper sections 4.2 and 4.3), and
// their CPU twins:
//   distance field DT (surface alignment): exact Euclidean distance in mm from
//     each object voxel to the nearest background voxel, with its gradient;
//   segment mask M (segment alignment): the segment indicator smoothed by a
//     Gaussian and encoded so that M >= 0.5 exactly at the segment's voxels.
// Both are R16F 3D textures of the field alone (2 bytes per voxel); the
// operator shader takes their gradient by central differences where it needs
// it (featureGradientOf in shaders/shared/feature.h). See
// shaders/shared/feature_bake.h.
#include "gpu/context.hpp"
#include "gpu/handle.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/resources.hpp"

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace cutaway::bake {

/// The format of both feature fields.
constexpr VkFormat kFeatureFieldFormat = VK_FORMAT_R16_SFLOAT;
/// The layout the feature fields rest in: sampled, and read as storage images
/// (the operator shaders load surface alignment's texels on CPU devices:
/// shaders/glsl/operator_sample.h, featureFiltered).
constexpr VkImageLayout kFeatureLayout = VK_IMAGE_LAYOUT_GENERAL;

class FeatureBaker {
public:
    explicit FeatureBaker(const gpu::Context& ctx);

    /// Surface alignment: the distance field DT. `values` is the uploaded volume
    /// texture (R16_UNORM or R8_UNORM, 3D, in its Image::layout; bake/volume_upload.hpp).
    /// A voxel is object when its normalized value > `threshold` (0..1), else background.
    /// Result: kFeatureFieldFormat (R16F), same extent, kFeatureLayout, usage
    /// SAMPLED | STORAGE | TRANSFER_SRC: the exact Euclidean distance in mm from the voxel
    /// centre to the nearest background voxel centre (0 for background; 65504, the largest
    /// half, when there is no background voxel at all); anisotropic spacing honoured.
    /// Throws InputError when a side is longer than 1024 voxels.
    gpu::Image distanceField(const gpu::Image& values, glm::dvec3 spacing, float threshold) const;

    /// Segment alignment: the smoothed feature mask M. `indicator` has one byte per
    /// voxel (x fastest), non-zero inside the segment of interest. It is smoothed by a
    /// separable Gaussian of sigma = bandMm / 2 mm (per axis sigma / spacing voxels;
    /// radius ceil(3 sigma) voxels, at most 32; bandMm == 0: no smoothing), borders
    /// clamped. Result as for distanceField: maskEncode(s, inside) of
    /// shared/feature_bake.h, s the smoothed indicator: max(s, 0.5) inside, min(s, 0.498)
    /// outside.
    gpu::Image segmentMask(const std::vector<uint8_t>& indicator, glm::ivec3 dims,
                           glm::dvec3 spacing, double bandMm) const;
    /// The same from the indicator already uploaded: an R8_UNORM 3D texture,
    /// 1 inside (see uploadMask).
    gpu::Image segmentMask(const gpu::Image& indicator, glm::dvec3 spacing, double bandMm) const;

private:
    /// mask_blur's windows (its taps live in registers): a pipeline per
    /// size, for radii up to each (voxels), the last kBlurMaxRadius.
    static constexpr std::array<int, 4> kBlurWindows{4, 8, 16, 32};
    VkPipeline blurPipeline(int radius) const;
    /// A set with every binding written: 0 `texture` (sampled: values or a
    /// mask), 1 `src`, 2 `dst` and 3 `out` (r16f storage,
    /// may be one image, in GENERAL).
    gpu::DescriptorSet makeSet(const gpu::Image& texture, const gpu::Image& src,
                               const gpu::Image& dst, const gpu::Image& out) const;

    const gpu::Context& m_ctx;
    gpu::DescriptorSetLayoutHandle m_setLayout;
    gpu::PipelineLayoutHandle m_layout;
    gpu::PipelineHandle m_lines;
    gpu::PipelineHandle m_envelope;
    gpu::ShaderModuleHandle m_blurModule;
    mutable std::array<gpu::PipelineHandle, kBlurWindows.size()> m_blurWindow; ///< made when needed
    gpu::PipelineHandle m_finish;
    gpu::SamplerHandle m_sampler;
};

/// The distance field's w on the CPU (same definition; `object` non-zero = object),
/// by the same exact separable transform in double precision. Millimetres.
std::vector<float> distanceFieldCpu(const std::vector<uint8_t>& object, glm::ivec3 dims,
                                    glm::dvec3 spacing);

/// The segment mask's w on the CPU (same smoothing and encoding as segmentMask).
std::vector<float> smoothMaskCpu(const std::vector<uint8_t>& indicator, glm::ivec3 dims,
                                 glm::dvec3 spacing, double bandMm);

} // namespace cutaway::bake

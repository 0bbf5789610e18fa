#include "bake/feature_bake.hpp"

#include "bake/volume_upload.hpp"
#include "core/error.hpp"
#include "edt_envelope_comp.spv.h"
#include "edt_lines_comp.spv.h"
#include "field_finish_comp.spv.h"
#include "mask_blur_comp.spv.h"
#include "shared/feature_bake.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

namespace cutaway::bake {
namespace {

constexpr VkImageUsageFlags kFieldUsage =
    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;

/// The Gaussian along one axis: sigma in voxels and the kernel radius.
struct BlurAxis {
    float sigma = 0.0f;
    int radius = 0;
};

BlurAxis blurAxis(glm::dvec3 spacing, double bandMm, int axis) {
    BlurAxis b;
    if (bandMm <= 0.0) return b;
    b.sigma = static_cast<float>(bandMm / 2.0 / spacing[axis]);
    b.radius = std::min(static_cast<int>(std::ceil(3.0 * double(b.sigma))), shader::kBlurMaxRadius);
    return b;
}

std::string dimsText(glm::ivec3 d) {
    return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
}

void checkGrid(glm::ivec3 dims, glm::dvec3 spacing, const char* what) {
    if (dims.x < 1 || dims.y < 1 || dims.z < 1)
        throw InputError(std::string(what) + ": empty volume (" + dimsText(dims) + " voxels)");
    for (int a = 0; a < 3; ++a)
        if (!(spacing[a] > 0.0) || !std::isfinite(spacing[a]))
            throw InputError(std::string(what) + ": voxel spacing must be positive and finite");
}

std::size_t voxelCount(glm::ivec3 d) {
    return std::size_t(d.x) * std::size_t(d.y) * std::size_t(d.z);
}

std::size_t voxelIndex(glm::ivec3 d, int x, int y, int z) {
    return std::size_t(x) + std::size_t(d.x) * (std::size_t(y) + std::size_t(d.y) * std::size_t(z));
}

shader::FeatureBakeParams baseParams(glm::ivec3 dims, glm::dvec3 spacing) {
    shader::FeatureBakeParams p{};
    p.dims = dims;
    p.spacing = glm::vec3(spacing);
    return p;
}

uint32_t groups(int n, int size) {
    return uint32_t((n + size - 1) / size);
}

struct Pass {
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
    shader::FeatureBakeParams params{};
    glm::uvec3 groups{1};
};

/// Makes one pass's storage writes visible to the next pass's reads and
/// orders its reads before the next pass's writes.
void storageBarrier(VkCommandBuffer cmd) {
    VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    barrier.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    barrier.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    barrier.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    barrier.dstAccessMask =
        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dep);
}

// What the GPU segment mask and its CPU twin both require of their inputs.
void checkSegmentInputs(const std::vector<uint8_t>& indicator, glm::ivec3 dims, glm::dvec3 spacing,
                        double bandMm) {
    checkGrid(dims, spacing, "segment mask");
    if (indicator.size() != voxelCount(dims))
        throw InputError("segment mask: " + std::to_string(indicator.size()) +
                         " indicator bytes for " + dimsText(dims) + " voxels");
    if (!(bandMm >= 0.0) || !std::isfinite(bandMm))
        throw InputError("segment mask: the band width must be a finite number >= 0 mm");
}

// field_finish.comp: 8x8 invocations per group, one voxel each.
glm::uvec3 finishGroups(glm::ivec3 dims) {
    return {groups(dims.x, 8), groups(dims.y, 8), uint32_t(dims.z)};
}

/// Records the passes in order in one submission: `out` goes to GENERAL
/// first and ends in kFeatureLayout. Blocks until done.
void runPasses(const gpu::Context& ctx, VkPipelineLayout layout, const gpu::Image& out,
               const std::vector<Pass>& passes) {
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        gpu::transition(cmd, out, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                        VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        for (std::size_t i = 0; i < passes.size(); ++i) {
            const Pass& pass = passes[i];
            if (i > 0) storageBarrier(cmd);
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass.pipeline);
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &pass.set, 0,
                                    nullptr);
            vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(pass.params),
                               &pass.params);
            vkCmdDispatch(cmd, pass.groups.x, pass.groups.y, pass.groups.z);
        }
        gpu::transition(cmd, out, VK_IMAGE_LAYOUT_GENERAL, kFeatureLayout,
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                        VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                            VK_ACCESS_2_TRANSFER_READ_BIT);
    });
}

/// out[p] = min over q of f[q] + w2 (p - q)^2, infinite f[q] left out (all
/// infinite: out infinite). The lower envelope of parabolas, as in the shader.
void envelope(const std::vector<double>& f, double w2, std::vector<double>& out,
              std::vector<int>& v, std::vector<double>& z) {
    const int n = static_cast<int>(f.size());
    const double inf = std::numeric_limits<double>::infinity();
    v.resize(std::size_t(n));
    z.resize(std::size_t(n) + 1);
    auto cross = [&](int q, int r) {
        return ((f[std::size_t(q)] - f[std::size_t(r)]) / w2 + double(q) * q - double(r) * r) /
               (2.0 * double(q - r));
    };
    int k = -1;
    for (int q = 0; q < n; ++q) {
        if (std::isinf(f[std::size_t(q)])) continue;
        if (k < 0) {
            k = 0;
            v[0] = q;
            z[0] = -inf;
            z[1] = inf;
            continue;
        }
        double s = cross(q, v[std::size_t(k)]);
        while (s <= z[std::size_t(k)]) {
            --k;
            s = cross(q, v[std::size_t(k)]);
        }
        ++k;
        v[std::size_t(k)] = q;
        z[std::size_t(k)] = s;
        z[std::size_t(k) + 1] = inf;
    }
    out.assign(std::size_t(n), inf);
    if (k < 0) return;
    k = 0;
    for (int p = 0; p < n; ++p) {
        while (z[std::size_t(k) + 1] < double(p))
            ++k;
        const int q = v[std::size_t(k)];
        out[std::size_t(p)] = w2 * double(p - q) * double(p - q) + f[std::size_t(q)];
    }
}

/// Calls fn(index of the line's first voxel) for every line of voxels along `axis`;
/// the line's voxels follow at axisStride(dims, axis).
template <typename Fn>
void forEachLine(glm::ivec3 dims, int axis, Fn&& fn) {
    const int u = axis == 0 ? 1 : 0;
    const int w = axis == 2 ? 1 : 2;
    for (int b = 0; b < dims[w]; ++b)
        for (int a = 0; a < dims[u]; ++a) {
            glm::ivec3 start(0);
            start[u] = a;
            start[w] = b;
            fn(voxelIndex(dims, start.x, start.y, start.z));
        }
}

std::size_t axisStride(glm::ivec3 dims, int axis) {
    return axis == 0 ? 1 : (axis == 1 ? std::size_t(dims.x) : std::size_t(dims.x) * dims.y);
}

} // namespace

FeatureBaker::FeatureBaker(const gpu::Context& ctx) : m_ctx(ctx) {
    const VkShaderStageFlags stage = VK_SHADER_STAGE_COMPUTE_BIT;
    const auto storage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    m_setLayout = gpu::createSetLayout(
        ctx,
        {{CW_FEATURE_BIND_SOURCE, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, stage, nullptr},
         {CW_FEATURE_BIND_SRC, storage, 1, stage, nullptr},
         {CW_FEATURE_BIND_DST, storage, 1, stage, nullptr},
         {CW_FEATURE_BIND_OUT, storage, 1, stage, nullptr}},
        "feature bake");
    m_layout =
        gpu::createPipelineLayout(ctx, m_setLayout.get(), sizeof(shader::FeatureBakeParams), stage);
    auto make = [&](const uint32_t* words, std::size_t bytes) {
        auto module = gpu::createShaderModule(ctx, words, bytes);
        return gpu::createComputePipeline(ctx, m_layout.get(), module.get());
    };
    m_lines = make(edt_lines_comp_spv, sizeof(edt_lines_comp_spv));
    m_envelope = make(edt_envelope_comp_spv, sizeof(edt_envelope_comp_spv));
    m_blurModule = gpu::createShaderModule(ctx, mask_blur_comp_spv, sizeof(mask_blur_comp_spv));
    m_finish = make(field_finish_comp_spv, sizeof(field_finish_comp_spv));
    m_sampler = gpu::createLinearSampler(ctx);
}

VkPipeline FeatureBaker::blurPipeline(int radius) const {
    static_assert(kBlurWindows.back() == shader::kBlurMaxRadius, "every radius needs a window");
    // Made when first needed: the window of 65 registers compiles in about 20 ms.
    std::size_t k = 0;
    while (k + 1 < kBlurWindows.size() && radius > kBlurWindows[k])
        ++k;
    if (!m_blurWindow[k]) {
        const VkSpecializationMapEntry entry{CW_FEATURE_SPEC_BLUR_WINDOW, 0, sizeof(int32_t)};
        const int32_t window = kBlurWindows[k];
        const VkSpecializationInfo info{1, &entry, sizeof window, &window};
        m_blurWindow[k] =
            gpu::createComputePipeline(m_ctx, m_layout.get(), m_blurModule.get(), &info);
    }
    return m_blurWindow[k].get();
}

gpu::DescriptorSet FeatureBaker::makeSet(const gpu::Image& texture, const gpu::Image& src,
                                         const gpu::Image& dst, const gpu::Image& out) const {
    gpu::DescriptorSet set = gpu::allocateDescriptorSet(
        m_ctx, m_setLayout.get(),
        {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1}, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 3}});
    gpu::writeImageDescriptor(m_ctx, set.set, CW_FEATURE_BIND_SOURCE,
                              VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, texture.view.get(),
                              texture.layout, m_sampler.get());
    const auto storage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    const auto general = VK_IMAGE_LAYOUT_GENERAL;
    gpu::writeImageDescriptor(m_ctx, set.set, CW_FEATURE_BIND_SRC, storage, src.view.get(),
                              general);
    gpu::writeImageDescriptor(m_ctx, set.set, CW_FEATURE_BIND_DST, storage, dst.view.get(),
                              general);
    gpu::writeImageDescriptor(m_ctx, set.set, CW_FEATURE_BIND_OUT, storage, out.view.get(),
                              general);
    return set;
}

namespace {

// The R16F field every pass works in, in place (each reads a whole line, or
// the part of it ahead, before writing it): a 4-byte scratch image would add
// 4 bytes per voxel to the peak memory.
gpu::Image makeField(const gpu::Context& ctx, VkExtent3D e) {
    return gpu::createImage(ctx, VK_IMAGE_TYPE_3D, kFeatureFieldFormat, e, kFieldUsage);
}

} // namespace

gpu::Image FeatureBaker::distanceField(const gpu::Image& values, glm::dvec3 spacing,
                                       float threshold) const {
    const VkExtent3D e = values.extent;
    const glm::ivec3 dims(int(e.width), int(e.height), int(e.depth));
    checkGrid(dims, spacing, "distance field");
    if (dims.x > shader::kEdtMaxLine || dims.y > shader::kEdtMaxLine ||
        dims.z > shader::kEdtMaxLine)
        throw InputError("distance field: the volume has " + dimsText(dims) +
                         " voxels; the distance transform handles at most " +
                         std::to_string(shader::kEdtMaxLine) + " voxels per side");

    gpu::Image out = makeField(m_ctx, e);
    gpu::DescriptorSet set = makeSet(values, out, out, out); // -> out, then in place

    shader::FeatureBakeParams p = baseParams(dims, spacing);
    p.threshold = threshold;
    std::vector<Pass> passes(3);
    passes[0] = {m_lines.get(), set.set, p, {groups(dims.y, 8), groups(dims.z, 8), 1}};
    p.axis = 1;
    passes[1] = {m_envelope.get(), set.set, p, {groups(dims.x, 8), groups(dims.z, 8), 1}};
    p.axis = 2;
    passes[2] = {m_envelope.get(), set.set, p, {groups(dims.x, 8), groups(dims.y, 8), 1}};
    runPasses(m_ctx, m_layout.get(), out, passes);
    out.layout = kFeatureLayout;
    return out;
}

gpu::Image FeatureBaker::segmentMask(const std::vector<uint8_t>& indicator, glm::ivec3 dims,
                                     glm::dvec3 spacing, double bandMm) const {
    checkSegmentInputs(indicator, dims, spacing, bandMm);
    return segmentMask(uploadMask(m_ctx, indicator, dims), spacing, bandMm);
}

gpu::Image FeatureBaker::segmentMask(const gpu::Image& texture, glm::dvec3 spacing,
                                     double bandMm) const {
    const VkExtent3D e = texture.extent;
    const glm::ivec3 dims(e.width, e.height, e.depth);
    checkGrid(dims, spacing, "segment mask");
    if (!(bandMm >= 0.0) || !std::isfinite(bandMm))
        throw InputError("segment mask: the band width must be a finite number >= 0 mm");

    gpu::Image out = makeField(m_ctx, e);
    // indicator -> out, then in place along y and z and to the encoded mask. A
    // blur pass reads each voxel of its line into a ring before it writes that
    // voxel.
    gpu::DescriptorSet set = makeSet(texture, out, out, out);

    const glm::uvec3 lineGroups[3] = {{groups(dims.y, 8), groups(dims.z, 8), 1},
                                      {groups(dims.x, 8), groups(dims.z, 8), 1},
                                      {groups(dims.x, 8), groups(dims.y, 8), 1}};
    std::vector<Pass> passes;
    for (int axis = 0; axis < 3; ++axis) {
        shader::FeatureBakeParams p = baseParams(dims, spacing);
        const BlurAxis blur = blurAxis(spacing, bandMm, axis);
        p.axis = axis;
        p.sigma = blur.sigma;
        p.radius = blur.radius;
        p.mode = axis == 0 ? 1 : 0;
        passes.push_back({blurPipeline(blur.radius), set.set, p, lineGroups[axis]});
    }
    shader::FeatureBakeParams p = baseParams(dims, spacing);
    p.mode = 1;
    passes.push_back({m_finish.get(), set.set, p, finishGroups(dims)});
    runPasses(m_ctx, m_layout.get(), out, passes);
    out.layout = kFeatureLayout;
    return out;
}

std::vector<float> distanceFieldCpu(const std::vector<uint8_t>& object, glm::ivec3 dims,
                                    glm::dvec3 spacing) {
    checkGrid(dims, spacing, "distance field");
    if (object.size() != voxelCount(dims))
        throw InputError("distance field: " + std::to_string(object.size()) + " mask bytes for " +
                         dimsText(dims) + " voxels");
    const double inf = std::numeric_limits<double>::infinity();
    // Squared distance to the background: 0 there, +inf in the object; then one
    // exact 1D transform per axis (the first one is the distance along x).
    std::vector<double> d2(object.size());
    for (std::size_t i = 0; i < object.size(); ++i)
        d2[i] = object[i] ? inf : 0.0;
    std::vector<double> line, result, z;
    std::vector<int> v;
    for (int axis = 0; axis < 3; ++axis) {
        const int n = dims[axis];
        const std::size_t stride = axisStride(dims, axis);
        const double w2 = spacing[axis] * spacing[axis];
        line.resize(std::size_t(n));
        forEachLine(dims, axis, [&](std::size_t start) {
            for (int i = 0; i < n; ++i)
                line[std::size_t(i)] = d2[start + std::size_t(i) * stride];
            envelope(line, w2, result, v, z);
            for (int i = 0; i < n; ++i)
                d2[start + std::size_t(i) * stride] = result[std::size_t(i)];
        });
    }
    std::vector<float> out(object.size());
    for (std::size_t i = 0; i < out.size(); ++i)
        out[i] = static_cast<float>(std::min(std::sqrt(d2[i]), double(shader::kHalfMax)));
    return out;
}

std::vector<float> smoothMaskCpu(const std::vector<uint8_t>& indicator, glm::ivec3 dims,
                                 glm::dvec3 spacing, double bandMm) {
    checkSegmentInputs(indicator, dims, spacing, bandMm);
    std::vector<float> s(indicator.size());
    for (std::size_t i = 0; i < s.size(); ++i)
        s[i] = indicator[i] ? 1.0f : 0.0f;
    // The same taps, in the same order, in float, as mask_blur.comp.glsl.
    std::vector<float> next(s.size());
    for (int axis = 0; axis < 3; ++axis) {
        const BlurAxis blur = blurAxis(spacing, bandMm, axis);
        std::vector<float> weights(std::size_t(blur.radius) + 1);
        for (int i = 0; i <= blur.radius; ++i)
            weights[std::size_t(i)] = shader::gaussianWeight(i, blur.sigma);
        const int n = dims[axis];
        const std::size_t stride = axisStride(dims, axis);
        forEachLine(dims, axis, [&](std::size_t start) {
            for (int p = 0; p < n; ++p) {
                float sum = 0.0f;
                float weightSum = 0.0f;
                for (int i = -blur.radius; i <= blur.radius; ++i) {
                    const float w = weights[std::size_t(std::abs(i))];
                    const int q = std::clamp(p + i, 0, n - 1);
                    sum += w * s[start + std::size_t(q) * stride];
                    weightSum += w;
                }
                next[start + std::size_t(p) * stride] = sum / weightSum;
            }
        });
        std::swap(s, next);
    }
    for (std::size_t i = 0; i < s.size(); ++i)
        s[i] = shader::maskEncode(s[i], indicator[i] != 0);
    return s;
}

} // namespace cutaway::bake

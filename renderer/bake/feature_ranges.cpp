#include "bake/feature_ranges.hpp"

#include "bake/feature_bake.hpp"
#include "feature_ranges_comp.spv.h"
#include "shared/feature_bake.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace cutaway::bake {
namespace {

// Steps to spare between a threshold and the ends of a byte's range.
constexpr double kSpareSteps = 2.0;

// Ranges over cells of `cellVoxels`^3 of a grid of `dims` voxels, not yet filled.
FieldRanges unfilled(glm::ivec3 dims, int cellVoxels, float scale) {
    FieldRanges r;
    r.cellVoxels = cellVoxels;
    r.scale = scale;
    r.cells = (dims + cellVoxels - 1) / cellVoxels;
    r.lohi.resize(2 * std::size_t(r.cells.x) * r.cells.y * r.cells.z);
    return r;
}

} // namespace

bool FieldRanges::mayReach(std::size_t i, double threshold) const {
    // A hair below: the shader's filter and mask round in float.
    return double(lohi[2 * i + 1]) >= threshold * scale - 1e-3;
}

bool FieldRanges::mayBeBelow(std::size_t i, double threshold) const {
    return double(lohi[2 * i]) < threshold * scale + 1e-3;
}

bool FieldRanges::resolves(double threshold) const {
    const double steps = threshold * double(scale);
    return steps > -128.0 + kSpareSteps && steps < 127.0 - kSpareSteps;
}

FieldRanges fieldRangesCpu(const std::vector<float>& field, glm::ivec3 dims, int cellVoxels,
                           float scale) {
    FieldRanges r = unfilled(dims, cellVoxels, scale);
    std::size_t i = 0;
    for (int cz = 0; cz < r.cells.z; ++cz)
        for (int cy = 0; cy < r.cells.y; ++cy)
            for (int cx = 0; cx < r.cells.x; ++cx, ++i) {
                const glm::ivec3 c(cx, cy, cz);
                const glm::ivec3 lo = glm::max(c * cellVoxels - 1, glm::ivec3(0));
                const glm::ivec3 hi = glm::min(c * cellVoxels + cellVoxels, dims - 1);
                float least = 1e30f, most = -1e30f;
                for (int z = lo.z; z <= hi.z; ++z)
                    for (int y = lo.y; y <= hi.y; ++y)
                        for (int x = lo.x; x <= hi.x; ++x) {
                            const float v =
                                field[std::size_t(x) +
                                      std::size_t(dims.x) * (y + std::size_t(dims.y) * z)];
                            least = std::min(least, v);
                            most = std::max(most, v);
                        }
                const glm::ivec2 e = shader::encodeFieldRange(least, most, scale);
                r.lohi[2 * i] = int8_t(e.x);
                r.lohi[2 * i + 1] = int8_t(e.y);
            }
    return r;
}

FieldRangeBaker::FieldRangeBaker(const gpu::Context& ctx) : m_ctx(ctx) {
    const auto cs = VK_SHADER_STAGE_COMPUTE_BIT;
    m_setLayout = gpu::createSetLayout(
        ctx,
        {{CW_RANGES_BIND_FIELD, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, cs, nullptr},
         {CW_RANGES_BIND_OUT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, cs, nullptr}},
        "field ranges");
    m_layout =
        gpu::createPipelineLayout(ctx, m_setLayout.get(), sizeof(shader::FieldRangeParams), cs);
    auto module =
        gpu::createShaderModule(ctx, feature_ranges_comp_spv, sizeof(feature_ranges_comp_spv));
    m_pipeline = gpu::createComputePipeline(ctx, m_layout.get(), module.get());
}

FieldRanges FieldRangeBaker::ranges(const gpu::Image& field, int cellVoxels, float scale) const {
    const glm::ivec3 dims(field.extent.width, field.extent.height, field.extent.depth);
    FieldRanges r = unfilled(dims, cellVoxels, scale);
    const glm::uvec3 n(r.cells);
    gpu::Image out = gpu::createImage(m_ctx, VK_IMAGE_TYPE_3D, VK_FORMAT_R8G8_SINT, {n.x, n.y, n.z},
                                      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    gpu::DescriptorSet set = gpu::allocateDescriptorSet(m_ctx, m_setLayout.get(),
                                                        {{VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 2}});
    gpu::writeImageDescriptor(m_ctx, set.set, CW_RANGES_BIND_FIELD,
                              VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, field.view.get(), kFeatureLayout);
    gpu::writeImageDescriptor(m_ctx, set.set, CW_RANGES_BIND_OUT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                              out.view.get(), VK_IMAGE_LAYOUT_GENERAL);
    shader::FieldRangeParams params{};
    params.dims = dims;
    params.cellVoxels = cellVoxels;
    params.scale = scale;
    // One invocation per pair of cells in x, for their whole column in z.
    gpu::computeIntoImage(m_ctx, out, m_pipeline.get(), m_layout.get(), set.set, &params,
                          sizeof params, glm::uvec3(8, 8, 1), VK_IMAGE_LAYOUT_GENERAL,
                          glm::uvec3((n.x + 1) / 2, n.y, 1));
    const std::vector<std::byte> bytes = gpu::downloadImage(m_ctx, out, VK_IMAGE_LAYOUT_GENERAL, 2);
    std::memcpy(r.lohi.data(), bytes.data(), r.lohi.size());
    return r;
}

} // namespace cutaway::bake

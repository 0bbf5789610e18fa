#include "bake/gradient_bake.hpp"

#include "bake/volume_upload.hpp"
#include "gpu/pipeline.hpp"
#include "gradient_comp.spv.h"
#include "gradient_storage_comp.spv.h"
#include "shared/gradient.h"

#include <algorithm>
#include <array>

namespace cutaway::bake {

GradientBaker::GradientBaker(const gpu::Context& ctx) : GradientBaker(ctx, ctx.tuning()) {}

GradientBaker::GradientBaker(const gpu::Context& ctx, const gpu::DeviceTuning& tuning)
    : m_ctx(ctx), m_tuning(ctx.supported(tuning)), m_valueBindings(ctx) {
    const auto compute = VK_SHADER_STAGE_COMPUTE_BIT;
    std::vector<VkDescriptorSetLayoutBinding> bindings{
        {CW_GRADIENT_BIND_VALUES, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, compute, nullptr},
        {CW_GRADIENT_BIND_OUT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, compute, nullptr}};
    if (m_tuning.storageValues) // the storage flavour's bindings
        for (uint32_t b : {CW_GRADIENT_BIND_VALUES_R8, CW_GRADIENT_BIND_VALUES_R16})
            bindings.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, compute, nullptr});
    m_setLayout = gpu::createSetLayout(ctx, bindings, "gradient bake");
    m_layout =
        gpu::createPipelineLayout(ctx, m_setLayout.get(), sizeof(shader::GradientParams), compute);
    m_module =
        gpu::createShaderModule(ctx, m_tuning.storageValues ? gpu::spirv(gradient_storage_comp_spv)
                                                            : gpu::spirv(gradient_comp_spv));
    m_sampler = gpu::createLinearSampler(ctx);
}

VkPipeline GradientBaker::pipelineFor(int fetch) const {
    const std::lock_guard<std::mutex> lock(m_pipelinesMutex);
    if (!m_pipelines[fetch]) {
        const int32_t constant = fetch;
        const VkSpecializationMapEntry entry{CW_GRADIENT_SPEC_STORAGE_FETCH, 0, sizeof constant};
        const VkSpecializationInfo info{1, &entry, sizeof constant, &constant};
        m_pipelines[fetch] =
            gpu::createComputePipeline(m_ctx, m_layout.get(), m_module.get(), &info);
    }
    return m_pipelines[fetch].get();
}

GradientLayout gradientLayoutFor(const gpu::Context& ctx, const gpu::DeviceTuning& tuning,
                                 glm::ivec3 dims) {
    if (!tuning.brickedGradients) return GradientLayout::Linear;
    const glm::ivec3 extent = shader::gradientBrickExtent(dims);
    const int most = static_cast<int>(ctx.properties().limits.maxImageDimension3D);
    return std::max({extent.x, extent.y, extent.z}) <= most ? GradientLayout::Bricked
                                                            : GradientLayout::Linear;
}

gpu::Image GradientBaker::bake(const gpu::Image& values, glm::dvec3 spacing) const {
    const VkExtent3D e = values.extent;
    return bake(values, spacing,
                gradientLayoutFor(m_ctx, m_tuning, glm::ivec3(e.width, e.height, e.depth)));
}

gpu::Image GradientBaker::bake(const gpu::Image& values, glm::dvec3 spacing,
                               GradientLayout layout) const {
    const glm::ivec3 dims(values.extent.width, values.extent.height, values.extent.depth);
    const bool bricked = layout == GradientLayout::Bricked;
    const glm::ivec3 size = bricked ? shader::gradientBrickExtent(dims) : dims;
    gpu::Image out = gpu::createImage(m_ctx, VK_IMAGE_TYPE_3D, VK_FORMAT_R8G8B8A8_SNORM,
                                      {static_cast<uint32_t>(size.x), static_cast<uint32_t>(size.y),
                                       static_cast<uint32_t>(size.z)},
                                      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                          VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    out.layout = bricked || m_tuning.storageImages() ? VK_IMAGE_LAYOUT_GENERAL
                                                     : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    gpu::DescriptorSet set = gpu::allocateDescriptorSet(
        m_ctx, m_setLayout.get(),
        {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1},
         {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, m_tuning.storageValues ? 3u : 1u}});
    gpu::writeImageDescriptor(m_ctx, set.set, CW_GRADIENT_BIND_VALUES,
                              VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, values.view.get(),
                              values.layout, m_sampler.get());
    gpu::writeImageDescriptor(m_ctx, set.set, CW_GRADIENT_BIND_OUT,
                              VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, out.view.get(),
                              VK_IMAGE_LAYOUT_GENERAL);
    if (m_tuning.storageValues) {
        std::array<VkImageView, 2> storage{};
        {
            const std::lock_guard<std::mutex> lock(m_pipelinesMutex); // stand-ins made once
            storage = m_valueBindings.views(values);
        }
        for (uint32_t i = 0; i < 2; ++i)
            gpu::writeImageDescriptor(m_ctx, set.set, CW_GRADIENT_BIND_VALUES_R8 + i,
                                      VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, storage[i],
                                      VK_IMAGE_LAYOUT_GENERAL);
    }

    shader::GradientParams params{};
    params.dims = dims;
    params.bricked = bricked ? 1 : 0;
    params.magnitudeScale = static_cast<float>(2.0 * std::min({spacing.x, spacing.y, spacing.z}));
    params.halfInvSpacing = glm::vec3(0.5 / spacing);

    // The groups cover the grid (kRun wide, kColumn deep), not the bricked image.
    const int fetch = m_tuning.storageValues ? ValueStorageBindings::fetchOf(values) : 0;
    gpu::computeIntoImage(m_ctx, out, pipelineFor(fetch), m_layout.get(), set.set, &params,
                          sizeof(params), glm::uvec3(8 * 4, 8, 16), out.layout, glm::uvec3(dims));
    return out;
}

} // namespace cutaway::bake

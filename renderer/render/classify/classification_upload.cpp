#include "render/classify/classification_upload.hpp"

#include "render/classify/label_classes.hpp"
#include "render/classify/preintegration.hpp"
#include "render/classify/transfer_table.hpp"

#include <glm/gtc/packing.hpp>

namespace cutaway::render {

gpu::Image uploadTransfer(const gpu::Context& ctx, const Scene& scene, const GpuVolume& volume,
                          double sliceMm) {
    const std::vector<const TransferFunction*> functions =
        classifyingTransfers(scene, volume.labels != nullptr);
    const bool preintegrated = scene.render.classification == Classification::Preintegrated;
    const uint32_t width = preintegrated ? kPreintegrationSize : kTransferTableSize;
    const uint32_t height = preintegrated ? kPreintegrationSize : 1;
    std::vector<uint64_t> halves;
    halves.reserve(std::size_t(width) * height * functions.size());
    for (const TransferFunction* tf : functions) {
        std::vector<glm::vec4> table = tabulateTransfer(*tf, volume.window);
        if (preintegrated)
            table = preintegrate(table, opacityUnit(scene, volume.smallestSpacing()), sliceMm);
        for (const glm::vec4& entry : table)
            halves.push_back(glm::packHalf4x16(entry));
    }
    const auto layers = static_cast<uint32_t>(functions.size());
    const auto usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    const auto stages = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT; // slicing and ray casting
    gpu::Image table =
        gpu::createImageArray(ctx, VK_FORMAT_R16G16B16A16_SFLOAT, {width, height}, layers, usage);
    table.layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    gpu::uploadImage(ctx, table, halves.data(), halves.size() * sizeof(uint64_t), table.layout,
                     stages);
    return table;
}

gpu::Image uploadClasses(const gpu::Context& ctx, const Scene& scene, const GpuVolume& volume,
                         std::int64_t& lowest) {
    const VkPipelineStageFlags2 readers =
        VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    const VkExtent3D extent{uint32_t(volume.dims.x), uint32_t(volume.dims.y),
                            uint32_t(volume.dims.z)};
    if (volume.labels && scene.output.labelAovs()) {
        const LabelChannelTexels texels(*volume.labels, scene.labelTransfers, scene.output.mattes);
        lowest = texels.lowest();
        return gpu::createSampledVolume(
            ctx, VK_FORMAT_R32_UINT, extent, 4,
            [&](std::size_t first, std::size_t count, std::byte* dst) {
                texels.write(first, count, reinterpret_cast<std::uint32_t*>(dst));
            },
            readers);
    }
    if (!volume.labels || scene.labelTransfers.empty()) {
        const std::uint8_t none = 0;
        return gpu::createSampledVolume(ctx, VK_FORMAT_R8_UINT, {1, 1, 1}, &none, 1, readers);
    }
    const LabelBytes layers = classLayers(*volume.labels, scene.labelTransfers);
    return gpu::createSampledVolume(
        ctx, VK_FORMAT_R8_UINT, extent, 1,
        [&](std::size_t first, std::size_t count, std::byte* dst) {
            layers.write(first, count, reinterpret_cast<std::uint8_t*>(dst));
        },
        readers);
}

void ClassificationTables::update(const Scene& scene, const GpuVolume& volume, double sliceMm) {
    const bool withLabels = volume.labels != nullptr;
    TransferKey transferKey{scene.render.classification == Classification::Preintegrated,
                            volume.window,
                            sliceMm,
                            opacityUnit(scene, volume.smallestSpacing()),
                            {}};
    for (const TransferFunction* tf : classifyingTransfers(scene, withLabels))
        transferKey.functions.push_back(*tf);
    if (!m_transfer.image || m_transferKey != transferKey) {
        m_transfer = uploadTransfer(m_ctx, scene, volume, sliceMm);
        m_transferKey = std::move(transferKey);
    }
    ClassesKey classesKey{volume.serial, {}, withLabels && scene.output.labelAovs(), {}};
    if (withLabels)
        for (const LabelTransfer& t : scene.labelTransfers)
            classesKey.ids.push_back(t.ids);
    if (classesKey.channels)
        for (const Matte& m : scene.output.mattes)
            classesKey.mattes.push_back(m.id);
    if (!m_classes.image || m_classesKey != classesKey) {
        m_classes = uploadClasses(m_ctx, scene, volume, m_lowestLabel);
        m_classesKey = std::move(classesKey);
    }
}

} // namespace cutaway::render

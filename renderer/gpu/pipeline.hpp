#pragma once
// Small builders for the few pipelines cutaway has: shader modules from
// embedded SPIR-V, descriptor set layouts from a list of bindings, compute
// pipelines. The graphics pipeline lives with the renderer that uses it.
#include "gpu/context.hpp"
#include "gpu/handle.hpp"
#include "gpu/resources.hpp"

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <vector>
#include <vulkan/vulkan.h>

namespace cutaway::gpu {

/// `words` points at SPIR-V as generated into NAME_STAGE.spv.h.
ShaderModuleHandle createShaderModule(const Context& ctx, const uint32_t* words, std::size_t bytes);

/// Embedded SPIR-V (a NAME_STAGE_spv array), to pick among a shader's flavours.
struct Spirv {
    const uint32_t* words;
    std::size_t bytes;
};
template <std::size_t N>
Spirv spirv(const uint32_t (&words)[N]) {
    return {words, sizeof words};
}
inline ShaderModuleHandle createShaderModule(const Context& ctx, Spirv code) {
    return createShaderModule(ctx, code.words, code.bytes);
}

/// `name` says whose set it is ("slicing frame", "operator"): the Context
/// keeps a record of each (Context::setLayouts).
DescriptorSetLayoutHandle createSetLayout(const Context& ctx,
                                          const std::vector<VkDescriptorSetLayoutBinding>& bindings,
                                          const char* name);

PipelineLayoutHandle createPipelineLayout(const Context& ctx, VkDescriptorSetLayout setLayout,
                                          uint32_t pushConstantBytes,
                                          VkShaderStageFlags pushStages);

/// A layout with several descriptor sets (set i = setLayouts[i]) and no push constants.
PipelineLayoutHandle createPipelineLayout(const Context& ctx,
                                          const std::vector<VkDescriptorSetLayout>& setLayouts,
                                          uint32_t pushConstantBytes = 0,
                                          VkShaderStageFlags pushStages = 0);

PipelineHandle createComputePipeline(const Context& ctx, VkPipelineLayout layout,
                                     VkShaderModule module,
                                     const VkSpecializationInfo* constants = nullptr);

/// What differs between cutaway's graphics pipelines. The rest is shared:
/// triangle lists, no culling (slice winding depends on the view; tool models
/// are not always closed), one sample, one viewport and scissor (dynamic),
/// dynamic rendering with the context's depth-stencil format.
struct GraphicsPipelineParts {
    VkShaderModule vertex = VK_NULL_HANDLE;
    VkShaderModule fragment = VK_NULL_HANDLE;
    std::vector<VkVertexInputBindingDescription> bindings;
    std::vector<VkVertexInputAttributeDescription> attributes;
    VkPipelineDepthStencilStateCreateInfo depthStencil{
        VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    std::vector<VkPipelineColorBlendAttachmentState> blends; ///< one per colour attachment
    std::vector<VkFormat> colorFormats;                      ///< one per colour attachment
    std::vector<VkDynamicState> extraDynamicStates;          ///< besides viewport and scissor
    const VkSpecializationInfo* fragmentConstants = nullptr; ///< specialization, or none
};
PipelineHandle createGraphicsPipeline(const Context& ctx, VkPipelineLayout layout,
                                      const GraphicsPipelineParts& parts);

/// Runs a compute pipeline that writes `target` (a storage image bound in
/// `set`), in groups of `groupSize` over `domain` (by default the image's
/// extent), then leaves `target` in `finalLayout` for fragment shaders,
/// compute shaders and copies. Blocks until done.
void computeIntoImage(const Context& ctx, const Image& target, VkPipeline pipeline,
                      VkPipelineLayout layout, VkDescriptorSet set, const void* push,
                      uint32_t pushBytes, glm::uvec3 groupSize,
                      VkImageLayout finalLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                      std::optional<glm::uvec3> domain = std::nullopt);

/// A pool sized for `sets` sets of the given descriptor counts, and one set from it.
struct DescriptorSet {
    DescriptorPoolHandle pool;
    VkDescriptorSet set = VK_NULL_HANDLE;
};
DescriptorSet allocateDescriptorSet(const Context& ctx, VkDescriptorSetLayout layout,
                                    const std::vector<VkDescriptorPoolSize>& sizes);

/// Writes one image descriptor (combined sampler or storage image).
void writeImageDescriptor(const Context& ctx, VkDescriptorSet set, uint32_t binding,
                          VkDescriptorType type, VkImageView view, VkImageLayout layout,
                          VkSampler sampler = VK_NULL_HANDLE);
void writeBufferDescriptor(const Context& ctx, VkDescriptorSet set, uint32_t binding,
                           VkDescriptorType type, VkBuffer buffer, VkDeviceSize size);

} // namespace cutaway::gpu

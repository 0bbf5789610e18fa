#include "gpu/pipeline.hpp"

#include "gpu/check.hpp"
#include "gpu/resources.hpp"

#include <stdexcept>
#include <string>

namespace cutaway::gpu {

ShaderModuleHandle createShaderModule(const Context& ctx, const uint32_t* words,
                                      std::size_t bytes) {
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = bytes;
    info.pCode = words;
    VkShaderModule module = VK_NULL_HANDLE;
    VK_CHECK(vkCreateShaderModule(ctx.device(), &info, nullptr, &module));
    return ShaderModuleHandle(ctx.device(), module);
}

DescriptorSetLayoutHandle createSetLayout(const Context& ctx,
                                          const std::vector<VkDescriptorSetLayoutBinding>& bindings,
                                          const char* name) {
    ctx.recordSetLayout({name, bindings});
    VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    info.bindingCount = static_cast<uint32_t>(bindings.size());
    info.pBindings = bindings.data();
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    VK_CHECK(vkCreateDescriptorSetLayout(ctx.device(), &info, nullptr, &layout));
    return DescriptorSetLayoutHandle(ctx.device(), layout);
}

PipelineLayoutHandle createPipelineLayout(const Context& ctx, VkDescriptorSetLayout setLayout,
                                          uint32_t pushConstantBytes,
                                          VkShaderStageFlags pushStages) {
    return createPipelineLayout(ctx, std::vector<VkDescriptorSetLayout>{setLayout},
                                pushConstantBytes, pushStages);
}

PipelineLayoutHandle createPipelineLayout(const Context& ctx,
                                          const std::vector<VkDescriptorSetLayout>& setLayouts,
                                          uint32_t pushConstantBytes,
                                          VkShaderStageFlags pushStages) {
    VkPushConstantRange range{pushStages, 0, pushConstantBytes};
    VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    info.setLayoutCount = static_cast<uint32_t>(setLayouts.size());
    info.pSetLayouts = setLayouts.data();
    info.pushConstantRangeCount = pushConstantBytes ? 1u : 0u;
    info.pPushConstantRanges = pushConstantBytes ? &range : nullptr;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VK_CHECK(vkCreatePipelineLayout(ctx.device(), &info, nullptr, &layout));
    return PipelineLayoutHandle(ctx.device(), layout);
}

PipelineHandle createComputePipeline(const Context& ctx, VkPipelineLayout layout,
                                     VkShaderModule module, const VkSpecializationInfo* constants) {
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.stage.pSpecializationInfo = constants;
    info.layout = layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VK_CHECK(vkCreateComputePipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
    return PipelineHandle(ctx.device(), pipeline);
}

void computeIntoImage(const Context& ctx, const Image& target, VkPipeline pipeline,
                      VkPipelineLayout layout, VkDescriptorSet set, const void* push,
                      uint32_t pushBytes, glm::uvec3 groupSize, VkImageLayout finalLayout,
                      std::optional<glm::uvec3> domain) {
    const glm::uvec3 e =
        domain.value_or(glm::uvec3(target.extent.width, target.extent.height, target.extent.depth));
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        transition(cmd, target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                   VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                   VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0,
                                nullptr);
        vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, pushBytes, push);
        const glm::uvec3 groups = (e + groupSize - 1u) / groupSize;
        vkCmdDispatch(cmd, groups.x, groups.y, groups.z);
        transition(cmd, target, VK_IMAGE_LAYOUT_GENERAL, finalLayout,
                   VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                   VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                       VK_ACCESS_2_TRANSFER_READ_BIT);
    });
}

DescriptorSet allocateDescriptorSet(const Context& ctx, VkDescriptorSetLayout layout,
                                    const std::vector<VkDescriptorPoolSize>& sizes) {
    DescriptorSet result;
    std::vector<VkDescriptorPoolSize> needed; // a type a layout lacks is asked for 0 times
    for (const VkDescriptorPoolSize& size : sizes)
        if (size.descriptorCount > 0) needed.push_back(size);
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = static_cast<uint32_t>(needed.size());
    poolInfo.pPoolSizes = needed.data();
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VK_CHECK(vkCreateDescriptorPool(ctx.device(), &poolInfo, nullptr, &pool));
    result.pool = DescriptorPoolHandle(ctx.device(), pool);
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = pool;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &layout;
    VK_CHECK(vkAllocateDescriptorSets(ctx.device(), &alloc, &result.set));
    return result;
}

void writeImageDescriptor(const Context& ctx, VkDescriptorSet set, uint32_t binding,
                          VkDescriptorType type, VkImageView view, VkImageLayout layout,
                          VkSampler sampler) {
    // An image whose maker did not record its resting layout (Image::layout).
    if (layout == VK_IMAGE_LAYOUT_UNDEFINED)
        throw std::logic_error("a descriptor of binding " + std::to_string(binding) +
                               " names an image in no layout");
    VkDescriptorImageInfo image{sampler, view, layout};
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set;
    write.dstBinding = binding;
    write.descriptorCount = 1;
    write.descriptorType = type;
    write.pImageInfo = &image;
    vkUpdateDescriptorSets(ctx.device(), 1, &write, 0, nullptr);
}

void writeBufferDescriptor(const Context& ctx, VkDescriptorSet set, uint32_t binding,
                           VkDescriptorType type, VkBuffer buffer, VkDeviceSize size) {
    VkDescriptorBufferInfo info{buffer, 0, size};
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set;
    write.dstBinding = binding;
    write.descriptorCount = 1;
    write.descriptorType = type;
    write.pBufferInfo = &info;
    vkUpdateDescriptorSets(ctx.device(), 1, &write, 0, nullptr);
}

PipelineHandle createGraphicsPipeline(const Context& ctx, VkPipelineLayout layout,
                                      const GraphicsPipelineParts& parts) {
    const VkPipelineShaderStageCreateInfo stages[2] = {
        {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0,
         VK_SHADER_STAGE_VERTEX_BIT, parts.vertex, "main", nullptr},
        {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0,
         VK_SHADER_STAGE_FRAGMENT_BIT, parts.fragment, "main", parts.fragmentConstants}};
    VkPipelineVertexInputStateCreateInfo vertexInput{
        VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vertexInput.vertexBindingDescriptionCount = static_cast<uint32_t>(parts.bindings.size());
    vertexInput.pVertexBindingDescriptions = parts.bindings.data();
    vertexInput.vertexAttributeDescriptionCount = static_cast<uint32_t>(parts.attributes.size());
    vertexInput.pVertexAttributeDescriptions = parts.attributes.data();
    VkPipelineInputAssemblyStateCreateInfo assembly{
        VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo viewport{
        VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{
        VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = VK_CULL_MODE_NONE;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{
        VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineColorBlendStateCreateInfo blendState{
        VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blendState.attachmentCount = static_cast<uint32_t>(parts.blends.size());
    blendState.pAttachments = parts.blends.data();
    std::vector<VkDynamicState> dynamicStates{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    dynamicStates.insert(dynamicStates.end(), parts.extraDynamicStates.begin(),
                         parts.extraDynamicStates.end());
    VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamic.dynamicStateCount = static_cast<uint32_t>(dynamicStates.size());
    dynamic.pDynamicStates = dynamicStates.data();
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = static_cast<uint32_t>(parts.colorFormats.size());
    rendering.pColorAttachmentFormats = parts.colorFormats.data();
    rendering.depthAttachmentFormat = ctx.formats().depthStencil;
    rendering.stencilAttachmentFormat = ctx.formats().depthStencil;

    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    info.pNext = &rendering;
    info.stageCount =
        parts.fragment != VK_NULL_HANDLE ? 2 : 1; // no fragment shader: depth/stencil only
    info.pStages = stages;
    info.pVertexInputState = &vertexInput;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &parts.depthStencil;
    info.pColorBlendState = &blendState;
    info.pDynamicState = &dynamic;
    info.layout = layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VK_CHECK(vkCreateGraphicsPipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
    return PipelineHandle(ctx.device(), pipeline);
}

} // namespace cutaway::gpu

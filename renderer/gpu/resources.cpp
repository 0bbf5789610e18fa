#include "gpu/resources.hpp"

#include "core/error.hpp"
#include "gpu/check.hpp"
#include "gpu/memory.hpp"

#include <algorithm>
#include <cstring>

namespace cutaway::gpu {

Buffer createBuffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage,
                    HostAccess access) {
    Buffer b;
    b.size = size;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer buffer = VK_NULL_HANDLE;
    VK_CHECK(vkCreateBuffer(ctx.device(), &info, nullptr, &buffer));
    b.buffer = BufferHandle(ctx.device(), buffer);

    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(ctx.device(), buffer, &req);
    b.memory = ctx.allocate(
        req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
        "a buffer of " + formatBytes(size),
        access == HostAccess::Read ? VK_MEMORY_PROPERTY_HOST_CACHED_BIT : 0);
    VK_CHECK(vkBindBufferMemory(ctx.device(), buffer, b.memory.get(), 0));
    VK_CHECK(vkMapMemory(ctx.device(), b.memory.get(), 0, size, 0, &b.mapped));
    return b;
}

namespace {

std::string describe(VkImageType type, VkFormat format, VkExtent3D extent, uint32_t layers) {
    // Built by appending: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string.
    std::string text = type == VK_IMAGE_TYPE_3D ? "a 3D image of " : "a 2D image of ";
    text += std::to_string(extent.width);
    text += 'x';
    text += std::to_string(extent.height);
    if (type == VK_IMAGE_TYPE_3D) {
        text += 'x';
        text += std::to_string(extent.depth);
    }
    if (layers > 1) {
        text += " with ";
        text += std::to_string(layers);
        text += " layers";
    }
    text += ' ';
    text += formatName(format);
    return text;
}

Image makeImage(const Context& ctx, VkImageType type, VkFormat format, VkExtent3D extent,
                VkImageUsageFlags usage, VkImageAspectFlags aspect, uint32_t layers,
                VkImageViewType viewType) {
    const auto& limits = ctx.properties().limits;
    const bool is3D = type == VK_IMAGE_TYPE_3D;
    const uint32_t maxDim = is3D ? limits.maxImageDimension3D : limits.maxImageDimension2D;
    if (extent.width > maxDim || extent.height > maxDim || extent.depth > maxDim)
        throw ResourceError("cannot create " + describe(type, format, extent, layers) + " on " +
                            ctx.deviceName() + ": a side exceeds the device's " +
                            (is3D ? "maxImageDimension3D" : "maxImageDimension2D") + " of " +
                            std::to_string(maxDim) + " texels");
    Image img;
    img.format = format;
    img.extent = extent;
    img.aspect = aspect;
    img.layers = layers;
    img.usage = usage;
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = type;
    info.format = format;
    info.extent = extent;
    info.mipLevels = 1;
    info.arrayLayers = layers;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage image = VK_NULL_HANDLE;
    VK_CHECK(vkCreateImage(ctx.device(), &info, nullptr, &image));
    img.image = ImageHandle(ctx.device(), image);

    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(ctx.device(), image, &req);
    img.memory = ctx.allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT,
                              describe(type, format, extent, layers));
    VK_CHECK(vkBindImageMemory(ctx.device(), image, img.memory.get(), 0));

    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = image;
    viewInfo.viewType = viewType;
    viewInfo.format = format;
    viewInfo.subresourceRange = {aspect, 0, 1, 0, layers};
    VkImageView view = VK_NULL_HANDLE;
    VK_CHECK(vkCreateImageView(ctx.device(), &viewInfo, nullptr, &view));
    img.view = ImageViewHandle(ctx.device(), view);
    return img;
}

} // namespace

Image createImage(const Context& ctx, VkImageType type, VkFormat format, VkExtent3D extent,
                  VkImageUsageFlags usage, VkImageAspectFlags aspect) {
    return makeImage(ctx, type, format, extent, usage, aspect, 1,
                     type == VK_IMAGE_TYPE_3D ? VK_IMAGE_VIEW_TYPE_3D : VK_IMAGE_VIEW_TYPE_2D);
}

ImageViewHandle createAspectView(const Context& ctx, const Image& image,
                                 VkImageAspectFlags aspect) {
    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = image.image.get();
    viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = image.format;
    viewInfo.subresourceRange = {aspect, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    VK_CHECK(vkCreateImageView(ctx.device(), &viewInfo, nullptr, &view));
    return ImageViewHandle(ctx.device(), view);
}

Image createImageArray(const Context& ctx, VkFormat format, VkExtent2D extent, uint32_t layers,
                       VkImageUsageFlags usage) {
    if (layers > ctx.properties().limits.maxImageArrayLayers)
        throw RuntimeError(std::to_string(layers) + " image layers exceed the device limit of " +
                           std::to_string(ctx.properties().limits.maxImageArrayLayers) + " (" +
                           ctx.deviceName() + ")");
    return makeImage(ctx, VK_IMAGE_TYPE_2D, format, {extent.width, extent.height, 1}, usage,
                     VK_IMAGE_ASPECT_COLOR_BIT, layers, VK_IMAGE_VIEW_TYPE_2D_ARRAY);
}

void transition(VkCommandBuffer cmd, const Image& image, VkImageLayout from, VkImageLayout to,
                VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
    VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    barrier.srcStageMask = srcStage;
    barrier.srcAccessMask = srcAccess;
    barrier.dstStageMask = dstStage;
    barrier.dstAccessMask = dstAccess;
    barrier.oldLayout = from;
    barrier.newLayout = to;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image.image.get();
    barrier.subresourceRange = {image.aspect, 0, 1, 0, image.layers};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dep);
}

void barrierTransferToHost(VkCommandBuffer cmd) {
    VkMemoryBarrier2 toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    toHost.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    toHost.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    toHost.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
    toHost.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &toHost;
    vkCmdPipelineBarrier2(cmd, &dep);
}

void uploadImage(const Context& ctx, const Image& image, std::size_t texelBytes,
                 const TexelWriter& write, VkImageLayout finalLayout,
                 VkPipelineStageFlags2 dstStage) {
    // A chunk is a run of whole z-slices (3D) or layers (arrays).
    const bool is3D = image.extent.depth > 1;
    const std::size_t sliceTexels = std::size_t(image.extent.width) * image.extent.height;
    const uint32_t slices = is3D ? image.extent.depth : image.layers;
    const uint32_t perChunk = static_cast<uint32_t>(
        std::clamp<std::size_t>(kStagingBytes / (sliceTexels * texelBytes), 1, slices));
    Buffer staging = createBuffer(ctx, perChunk * sliceTexels * texelBytes,
                                  VK_BUFFER_USAGE_TRANSFER_SRC_BIT, HostAccess::Write);
    for (uint32_t first = 0; first < slices; first += perChunk) {
        const uint32_t count = std::min(perChunk, slices - first);
        write(first * sliceTexels, count * sliceTexels, static_cast<std::byte*>(staging.mapped));
        ctx.submitAndWait([&](VkCommandBuffer cmd) {
            if (first == 0)
                transition(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED,
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE,
                           VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COPY_BIT,
                           VK_ACCESS_2_TRANSFER_WRITE_BIT);
            VkBufferImageCopy region{};
            region.imageSubresource = {image.aspect, 0, is3D ? 0 : first, is3D ? 1 : count};
            region.imageOffset = {0, 0, is3D ? static_cast<int32_t>(first) : 0};
            region.imageExtent = {image.extent.width, image.extent.height, is3D ? count : 1};
            vkCmdCopyBufferToImage(cmd, staging.buffer.get(), image.image.get(),
                                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
            if (first + count == slices)
                transition(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, finalLayout,
                           VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, dstStage,
                           VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
        });
    }
}

void uploadImage(const Context& ctx, const Image& image, const void* data, std::size_t bytes,
                 VkImageLayout finalLayout, VkPipelineStageFlags2 dstStage) {
    const std::size_t texels =
        std::size_t(image.extent.width) * image.extent.height * image.extent.depth * image.layers;
    if (texels == 0 || bytes % texels != 0)
        throw RuntimeError("uploadImage: " + std::to_string(bytes) + " bytes for " +
                           std::to_string(texels) + " texels");
    const std::size_t texelBytes = bytes / texels;
    const auto* src = static_cast<const std::byte*>(data);
    uploadImage(
        ctx, image, texelBytes,
        [&](std::size_t first, std::size_t count, std::byte* dst) {
            std::memcpy(dst, src + first * texelBytes, count * texelBytes);
        },
        finalLayout, dstStage);
}

Image createSampledVolume(const Context& ctx, VkFormat format, VkExtent3D extent,
                          std::size_t texelBytes, const TexelWriter& write,
                          VkPipelineStageFlags2 readers) {
    Image image = createImage(ctx, VK_IMAGE_TYPE_3D, format, extent,
                              VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    image.layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    uploadImage(ctx, image, texelBytes, write, image.layout, readers);
    return image;
}

namespace {

// A 3D image of `usage` (and TRANSFER_DST) holding `bytes` of tightly packed
// texels, left in `layout` for `readers`.
Image createFilledVolume(const Context& ctx, VkFormat format, VkExtent3D extent,
                         VkImageUsageFlags usage, VkImageLayout layout, const void* data,
                         std::size_t bytes, VkPipelineStageFlags2 readers) {
    Image image =
        createImage(ctx, VK_IMAGE_TYPE_3D, format, extent, usage | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    uploadImage(ctx, image, data, bytes, layout, readers);
    image.layout = layout;
    return image;
}

} // namespace

Image createSampledVolume(const Context& ctx, VkFormat format, VkExtent3D extent, const void* data,
                          std::size_t bytes, VkPipelineStageFlags2 readers) {
    return createFilledVolume(ctx, format, extent, VK_IMAGE_USAGE_SAMPLED_BIT,
                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, data, bytes, readers);
}

Image createStorageVolume(const Context& ctx, VkFormat format, VkExtent3D extent, const void* data,
                          std::size_t bytes, VkPipelineStageFlags2 readers) {
    return createFilledVolume(ctx, format, extent, VK_IMAGE_USAGE_STORAGE_BIT,
                              VK_IMAGE_LAYOUT_GENERAL, data, bytes, readers);
}

std::vector<std::byte> downloadImage(const Context& ctx, const Image& image, VkImageLayout layout,
                                     std::size_t bytesPerTexel) {
    const std::size_t bytes = bytesPerTexel * image.extent.width * image.extent.height *
                              image.extent.depth * image.layers;
    Buffer staging = createBuffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, HostAccess::Read);
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        transition(cmd, image, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                   VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferImageCopy region{};
        region.imageSubresource = {image.aspect, 0, 0, image.layers};
        region.imageExtent = image.extent;
        vkCmdCopyImageToBuffer(cmd, image.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               staging.buffer.get(), 1, &region);
        transition(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout,
                   VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                   VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT);
        barrierTransferToHost(cmd);
    });
    std::vector<std::byte> out(bytes);
    std::memcpy(out.data(), staging.mapped, bytes);
    return out;
}

namespace {

SamplerHandle createSampler(const Context& ctx, VkFilter filter) {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = filter;
    info.minFilter = filter;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    info.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    info.maxLod = 0.0f;
    VkSampler sampler = VK_NULL_HANDLE;
    VK_CHECK(vkCreateSampler(ctx.device(), &info, nullptr, &sampler));
    return SamplerHandle(ctx.device(), sampler);
}

} // namespace

SamplerHandle createLinearSampler(const Context& ctx) {
    return createSampler(ctx, VK_FILTER_LINEAR);
}

SamplerHandle createNearestSampler(const Context& ctx) {
    return createSampler(ctx, VK_FILTER_NEAREST);
}

} // namespace cutaway::gpu

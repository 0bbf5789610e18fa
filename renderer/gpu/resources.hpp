#pragma once
// Buffers and images with their own memory (one dedicated allocation each:
// cutaway holds a handful of large resources, so a sub-allocator would buy
// nothing), uploads through a staging buffer, and layout transitions.
#include "gpu/context.hpp"
#include "gpu/handle.hpp"
#include "shared/tuning.h"

#include <cstddef>
#include <functional>
#include <vector>
#include <vulkan/vulkan.h>

namespace cutaway::gpu {

struct Buffer {
    BufferHandle buffer;
    DeviceMemory memory;
    VkDeviceSize size = 0;
    void* mapped = nullptr; ///< the persistent mapping
};

/// Which way a buffer's data goes between the host and the device.
enum class HostAccess {
    Write, ///< the host writes, the device reads: uploads, uniforms, vertices
    Read,  ///< the device writes, the host reads: readbacks, on a HOST_CACHED type if any
};

/// A HOST_VISIBLE | HOST_COHERENT buffer, mapped for good. A readback's type
/// is also HOST_CACHED where the device has one (chooseMemoryType): on a
/// discrete GPU the first host-visible type is write-combined, fine for
/// writing and slow to read. lavapipe has one type with every flag.
Buffer createBuffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage,
                    HostAccess access);

struct Image {
    ImageHandle image;
    DeviceMemory memory;
    ImageViewHandle view;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent3D extent{0, 0, 0};
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    uint32_t layers = 1; ///< array layers (2D arrays); transfers and barriers cover them all
    VkImageUsageFlags usage = 0;
    /// The layout a texture rests in between passes, where its maker leaves
    /// it in one (uploads, bakes); descriptors that read it name this.
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
};

/// A device-local image of type 2D (extent.depth == 1) or 3D, with a view.
Image createImage(const Context& ctx, VkImageType type, VkFormat format, VkExtent3D extent,
                  VkImageUsageFlags usage, VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT);

/// Another 2D view of `image` showing only `aspect` (the depth of a
/// depth-stencil image, to sample it).
ImageViewHandle createAspectView(const Context& ctx, const Image& image, VkImageAspectFlags aspect);

/// A device-local 2D array image of `layers` layers with a 2D_ARRAY view
/// (also for one layer, so shaders can declare a sampler2DArray).
Image createImageArray(const Context& ctx, VkFormat format, VkExtent2D extent, uint32_t layers,
                       VkImageUsageFlags usage);

/// Records a layout transition with a full-image barrier (synchronization2).
void transition(VkCommandBuffer cmd, const Image& image, VkImageLayout from, VkImageLayout to,
                VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

/// Makes transfer writes (a copy into a host-visible buffer) visible to the host.
void barrierTransferToHost(VkCommandBuffer cmd);

/// Writes `count` texels, starting with texel `first` of the image (x fastest,
/// then y, then z or layer), tightly packed to `dst`.
using TexelWriter = std::function<void(std::size_t first, std::size_t count, std::byte* dst)>;

/// The most bytes an upload stages at once (at least one z-slice or layer).
inline constexpr std::size_t kStagingBytes = std::size_t(shader::kStagingMiB) << 20;

/// Fills the whole image with texels of `texelBytes` bytes that `write` makes,
/// a few z-slices (or layers) at a time through one staging buffer of at most
/// kStagingBytes, so no copy of the whole image exists on the host; leaves it
/// in `finalLayout`, readable by `dstStage`. Blocks until done.
void uploadImage(const Context& ctx, const Image& image, std::size_t texelBytes,
                 const TexelWriter& write, VkImageLayout finalLayout,
                 VkPipelineStageFlags2 dstStage);

/// Copies tightly packed texels (layer after layer) into the whole image and leaves it in
/// `finalLayout`, readable by `dstStage`. Blocks until done.
void uploadImage(const Context& ctx, const Image& image, const void* data, std::size_t bytes,
                 VkImageLayout finalLayout, VkPipelineStageFlags2 dstStage);

/// A sampled 3D image of `format` whose texels (of `texelBytes`) `write` makes,
/// left SHADER_READ_ONLY_OPTIMAL for `readers`. Blocks until done.
Image createSampledVolume(const Context& ctx, VkFormat format, VkExtent3D extent,
                          std::size_t texelBytes, const TexelWriter& write,
                          VkPipelineStageFlags2 readers);

/// A sampled 3D image of `format` holding `bytes` of tightly packed texels (x
/// fastest), left SHADER_READ_ONLY_OPTIMAL for `readers`. Blocks until done.
Image createSampledVolume(const Context& ctx, VkFormat format, VkExtent3D extent, const void* data,
                          std::size_t bytes, VkPipelineStageFlags2 readers);

/// A storage 3D image of `format` holding `bytes` of tightly packed texels (x
/// fastest), left GENERAL for `readers` (shaders read it with imageLoad: on
/// lavapipe an inline load, where a sampled texel fetch is a function call).
/// Blocks until done.
Image createStorageVolume(const Context& ctx, VkFormat format, VkExtent3D extent, const void* data,
                          std::size_t bytes, VkPipelineStageFlags2 readers);

/// Copies a whole image back to the host (tests and tools; blocks). The image
/// must be in `layout` (and readable by transfers after `srcStage`) and is
/// left in it.
std::vector<std::byte> downloadImage(const Context& ctx, const Image& image, VkImageLayout layout,
                                     std::size_t bytesPerTexel);

/// A linear-filtering, clamp-to-edge sampler.
SamplerHandle createLinearSampler(const Context& ctx);
/// A nearest-texel, clamp-to-edge sampler (integer textures read with texelFetch).
SamplerHandle createNearestSampler(const Context& ctx);

} // namespace cutaway::gpu

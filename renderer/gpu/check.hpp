#pragma once
// VK_CHECK: every Vulkan call that returns a VkResult goes through it, so a
// failure names the call, where it was made and the result code.
#include <string>
#include <vulkan/vulkan.h>

namespace cutaway::gpu {

/// "VK_ERROR_OUT_OF_DEVICE_MEMORY" etc.
const char* resultName(VkResult result);
/// "R16_UNORM" for the formats cutaway uses, for messages.
const char* formatName(VkFormat format);

/// Throws RuntimeError("CALL failed at FILE:LINE: RESULT (+ a hint for the common ones)").
[[noreturn]] void throwVkError(VkResult result, const char* call, const char* file, int line);

} // namespace cutaway::gpu

#define VK_CHECK(call)                                                                             \
    do {                                                                                           \
        VkResult vkCheckResult_ = (call);                                                          \
        if (vkCheckResult_ != VK_SUCCESS)                                                          \
            ::cutaway::gpu::throwVkError(vkCheckResult_, #call, __FILE__, __LINE__);               \
    } while (0)

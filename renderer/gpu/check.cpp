#include "gpu/check.hpp"

#include "core/error.hpp"

#include <filesystem>

namespace cutaway::gpu {

const char* resultName(VkResult result) {
    switch (result) {
#define CW_CASE(r)                                                                                 \
    case r:                                                                                        \
        return #r;
        CW_CASE(VK_SUCCESS)
        CW_CASE(VK_NOT_READY)
        CW_CASE(VK_TIMEOUT)
        CW_CASE(VK_INCOMPLETE)
        CW_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
        CW_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        CW_CASE(VK_ERROR_INITIALIZATION_FAILED)
        CW_CASE(VK_ERROR_DEVICE_LOST)
        CW_CASE(VK_ERROR_MEMORY_MAP_FAILED)
        CW_CASE(VK_ERROR_LAYER_NOT_PRESENT)
        CW_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        CW_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        CW_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        CW_CASE(VK_ERROR_TOO_MANY_OBJECTS)
        CW_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
        CW_CASE(VK_ERROR_FRAGMENTED_POOL)
        CW_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
        CW_CASE(VK_ERROR_UNKNOWN)
#undef CW_CASE
    default:
        return "VK_ERROR (unlisted code)";
    }
}

void throwVkError(VkResult result, const char* call, const char* file, int line) {
    std::string message = std::string(call) + " failed at " +
                          std::filesystem::path(file).filename().string() + ":" +
                          std::to_string(line) + ": " + resultName(result);
    if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY)
        message += " (out of memory: try a smaller volume, image size or operator resolution)";
    else if (result == VK_ERROR_DEVICE_LOST)
        message += " (the GPU driver reset the device; the frame is lost)";
    throw RuntimeError(message);
}

} // namespace cutaway::gpu

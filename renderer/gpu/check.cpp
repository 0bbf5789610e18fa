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

const char* formatName(VkFormat format) {
    switch (format) {
#define CW_CASE(f)                                                                                 \
    case VK_FORMAT_##f:                                                                            \
        return #f;
        CW_CASE(R8_UNORM)
        CW_CASE(R8_UINT)
        CW_CASE(R16_UNORM)
        CW_CASE(R32_SFLOAT)
        CW_CASE(R8G8B8A8_UNORM)
        CW_CASE(R8G8B8A8_SNORM)
        CW_CASE(R16G16B16A16_SFLOAT)
        CW_CASE(R32G32B32_SFLOAT)
        CW_CASE(R32G32B32A32_SFLOAT)
        CW_CASE(D24_UNORM_S8_UINT)
        CW_CASE(D32_SFLOAT_S8_UINT)
#undef CW_CASE
    default:
        return "(another format)";
    }
}

void throwVkError(VkResult result, const char* call, const char* file, int line) {
    std::string message = std::string(call) + " failed at " +
                          std::filesystem::path(file).filename().string() + ":" +
                          std::to_string(line) + ": " + resultName(result);
    if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY)
        throw ResourceError(message + " (out of memory: try a smaller volume, image size or "
                                      "operator resolution)");
    if (result == VK_ERROR_DEVICE_LOST)
        throw ResourceError(message + " (the device was lost: the driver reset it or it hung; "
                                      "the frame is lost, finished frames are whole)");
    throw RuntimeError(message);
}

} // namespace cutaway::gpu

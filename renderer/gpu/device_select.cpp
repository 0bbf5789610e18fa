#include "gpu/device_select.hpp"

#include "core/error.hpp"
#include "gpu/check.hpp"

#include <algorithm>
#include <cctype>

namespace cutaway::gpu {
namespace {

int typeRank(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
        return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
        return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
        return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
        return 1;
    default:
        return 0;
    }
}

const char* typeName(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
        return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
        return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
        return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
        return "CPU";
    default:
        return "other";
    }
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

bool hasFeatures(VkPhysicalDevice device, VkFormat format, VkImageTiling tiling,
                 VkFormatFeatureFlags wanted) {
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(device, format, &props);
    VkFormatFeatureFlags have = tiling == VK_IMAGE_TILING_OPTIMAL ? props.optimalTilingFeatures
                                                                  : props.linearTilingFeatures;
    return (have & wanted) == wanted;
}

// R8_UNORM and R16_UNORM can be storage images (DeviceFormats::storageValues).
bool storageValueFormats(VkPhysicalDevice device) {
    const auto opt = VK_IMAGE_TILING_OPTIMAL;
    return hasFeatures(device, VK_FORMAT_R8_UNORM, opt, VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) &&
           hasFeatures(device, VK_FORMAT_R16_UNORM, opt, VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT);
}

// Returns an empty string when the device fits, else the reason it does not.
std::string check(VkPhysicalDevice device, DeviceChoice& choice) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(device, &props);
    if (props.apiVersion < VK_API_VERSION_1_3) return "supports Vulkan 1.2 or older; 1.3 needed";

    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f13, {}};
    vkGetPhysicalDeviceFeatures2(device, &f2);
    if (!f13.dynamicRendering || !f13.synchronization2)
        return "lacks dynamicRendering or synchronization2";
    if (!f2.features.shaderStorageImageExtendedFormats)
        return "lacks shaderStorageImageExtendedFormats (R16F feature fields)";

    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
    const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    auto it = std::find_if(families.begin(), families.end(),
                           [&](const auto& f) { return (f.queueFlags & need) == need; });
    if (it == families.end()) return "no queue does both graphics and compute";
    choice.queueFamily = static_cast<uint32_t>(it - families.begin());

    const auto opt = VK_IMAGE_TILING_OPTIMAL;
    const VkFormatFeatureFlags sampledLinear =
        VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
    if (!hasFeatures(device, VK_FORMAT_R16_UNORM, opt,
                     sampledLinear | VK_FORMAT_FEATURE_TRANSFER_DST_BIT))
        return "cannot filter R16_UNORM volume textures";
    if (!hasFeatures(device, VK_FORMAT_R8G8B8A8_SNORM, opt,
                     sampledLinear | VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT))
        return "cannot store and filter RGBA8_SNORM gradient textures";
    if (!hasFeatures(device, VK_FORMAT_R16_SFLOAT, opt,
                     sampledLinear | VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT))
        return "cannot store and filter R16F feature fields";
    if (!hasFeatures(device, VK_FORMAT_R16G16B16A16_SFLOAT, opt, sampledLinear))
        return "cannot filter RGBA16F transfer-function textures";

    choice.formats.storageValues = storageValueFormats(device);

    const VkFormatFeatureFlags blendTarget = VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT |
                                             VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT |
                                             VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
    if (hasFeatures(device, VK_FORMAT_R32G32B32A32_SFLOAT, opt, blendTarget))
        choice.formats.color = VK_FORMAT_R32G32B32A32_SFLOAT;
    else if (hasFeatures(device, VK_FORMAT_R16G16B16A16_SFLOAT, opt, blendTarget))
        choice.formats.color = VK_FORMAT_R16G16B16A16_SFLOAT;
    else
        return "cannot blend into a float colour target";

    for (VkFormat f : {VK_FORMAT_D32_SFLOAT_S8_UINT, VK_FORMAT_D24_UNORM_S8_UINT}) {
        if (hasFeatures(device, f, opt, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT)) {
            choice.formats.depthStencil = f;
            break;
        }
    }
    if (choice.formats.depthStencil == VK_FORMAT_UNDEFINED) return "no depth-stencil format";
    return {};
}

} // namespace

std::string describeDevice(VkPhysicalDevice device) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(device, &props);
    return std::string(props.deviceName) + " (" + typeName(props.deviceType) + ", Vulkan " +
           std::to_string(VK_API_VERSION_MAJOR(props.apiVersion)) + "." +
           std::to_string(VK_API_VERSION_MINOR(props.apiVersion)) + ")";
}

DeviceChoice chooseDevice(VkInstance instance, const std::string& wanted) {
    uint32_t count = 0;
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    if (count == 0)
        throw RuntimeError("no Vulkan device: install mesa-vulkan-drivers (lavapipe, the CPU "
                           "implementation) or a GPU driver");
    std::vector<VkPhysicalDevice> devices(count);
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));

    DeviceChoice best;
    int bestRank = -1;
    std::string report;
    bool named = wanted.empty(); // some device's name matches --device
    for (VkPhysicalDevice device : devices) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(device, &props);
        std::string reason;
        DeviceChoice choice;
        if (!wanted.empty() && lower(props.deviceName).find(lower(wanted)) == std::string::npos)
            reason = "name does not match --device \"" + wanted + "\"";
        else
            named = true, reason = check(device, choice);
        report += "\n  " + describeDevice(device) + ": " + (reason.empty() ? "usable" : reason);
        if (reason.empty() && typeRank(props.deviceType) > bestRank) {
            bestRank = typeRank(props.deviceType);
            choice.device = device;
            best = choice;
        }
    }
    // A name that matches no device is a usage error (exit 2), as any bad argument.
    if (!named)
        throw InputError("--device \"" + wanted +
                         "\" names no Vulkan device; devices found:" + report);
    if (best.device == VK_NULL_HANDLE)
        throw RuntimeError("no Vulkan device fits cutaway's needs; devices found:" + report);
    return best;
}

bool hasComputeBallots(VkPhysicalDevice device) {
    VkPhysicalDeviceSubgroupProperties subgroup{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &subgroup, {}};
    vkGetPhysicalDeviceProperties2(device, &properties);
    return (subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) &&
           (subgroup.supportedOperations & VK_SUBGROUP_FEATURE_BALLOT_BIT);
}

DeviceTuning profileOf(VkPhysicalDevice device) {
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(device, &properties);
    return tuningFor(properties.deviceType, storageValueFormats(device), hasComputeBallots(device));
}

} // namespace cutaway::gpu

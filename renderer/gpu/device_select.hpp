#pragma once
// Picks the physical device; separate from context.cpp so the rules are easy to read.
#include "gpu/context.hpp"

#include <string>
#include <vector>
#include <vulkan/vulkan.h>

namespace cutaway::gpu {

struct DeviceChoice {
    VkPhysicalDevice device = VK_NULL_HANDLE;
    uint32_t queueFamily = 0;
    DeviceFormats formats;
};

/// Returns the best device that has everything cutaway needs; throws
/// RuntimeError listing each device and why it was rejected.
DeviceChoice chooseDevice(VkInstance instance, const std::string& wanted);

/// "NAME (TYPE, Vulkan X.Y)"
std::string describeDevice(VkPhysicalDevice device);

/// Whether compute shaders on `device` have subgroup ballots.
bool hasComputeBallots(VkPhysicalDevice device);

/// The paths `device` takes by its type and what it can run (device_tuning.hpp).
DeviceTuning profileOf(VkPhysicalDevice device);

} // namespace cutaway::gpu

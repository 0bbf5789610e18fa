#include "gpu/device_tuning.hpp"

namespace cutaway::gpu {

DeviceTuning supportedTuning(DeviceTuning wanted, bool storageFormats, bool computeBallots) {
    wanted.storageValues = wanted.storageValues && storageFormats;
    wanted.yieldLanes = wanted.yieldLanes && computeBallots;
    return wanted;
}

DeviceTuning tuningFor(VkPhysicalDeviceType type, bool storageFormats, bool computeBallots) {
    const bool cpu = type == VK_PHYSICAL_DEVICE_TYPE_CPU;
    return supportedTuning(cpu ? kCpuTuning : kGpuTuning, storageFormats, computeBallots);
}

const char* tuningName(const DeviceTuning& tuning) {
    if (tuning == kGpuTuning) return "gpu";
    if (tuning == kCpuTuning) return "cpu";
    return "custom";
}

} // namespace cutaway::gpu

// The device profiles (gpu/device_tuning.hpp) by device type and what the
// device can run; tests/gpu/device_tuning_test.cpp checks what a profile
// costs on a device.
#include "gpu/device_tuning.hpp"

#include <gtest/gtest.h>

namespace cutaway::test {
namespace {

TEST(DeviceTuning, CpuImplementationsTakeWhatTheyCanAndGpusNone) {
    const auto cpu = VK_PHYSICAL_DEVICE_TYPE_CPU;
    EXPECT_EQ(gpu::tuningFor(cpu, true, true), gpu::kCpuTuning);
    EXPECT_EQ(gpu::tuningFor(cpu, false, true), (gpu::DeviceTuning{false, true, true}));
    EXPECT_EQ(gpu::tuningFor(cpu, true, false), (gpu::DeviceTuning{true, true, false}));
    for (const auto type :
         {VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU,
          VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU})
        EXPECT_EQ(gpu::tuningFor(type, true, true), gpu::kGpuTuning);
    EXPECT_STREQ(gpu::tuningName(gpu::kGpuTuning), "gpu");
    EXPECT_STREQ(gpu::tuningName(gpu::kCpuTuning), "cpu");
}

} // namespace
} // namespace cutaway::test

// The Vulkan context: device choice, clear reasons when nothing fits, and the
// validation layer actually reporting (so "zero messages" means something).
#include "core/error.hpp"
#include "gpu/context.hpp"
#include "gpu_fixture.hpp"

#include <gtest/gtest.h>

namespace cutaway::test {

TEST_F(GpuTest, PicksADeviceWithTheFormatsCutawayNeeds) {
    EXPECT_FALSE(ctx().deviceName().empty());
    EXPECT_NE(ctx().formats().color, VK_FORMAT_UNDEFINED);
    EXPECT_NE(ctx().formats().depthStencil, VK_FORMAT_UNDEFINED);
    EXPECT_TRUE(ctx().validationEnabled());
}

TEST(GpuContext, UnknownDeviceNameListsTheDevicesAndWhy) {
    gpu::ContextOptions options;
    options.deviceName = "no-such-gpu-xyz";
    try {
        gpu::Context ctx(options);
        FAIL() << "expected an error for an unknown device name";
    } catch (const InputError& e) { // a usage error: exit 2
        const std::string what = e.what();
        EXPECT_NE(what.find("names no Vulkan device"), std::string::npos) << what;
        EXPECT_NE(what.find("does not match --device \"no-such-gpu-xyz\""), std::string::npos)
            << what;
    }
}

TEST(GpuContext, DeviceNameMatchesBySubstringIgnoringCase) {
    const auto devices = gpu::listDevices();
    ASSERT_FALSE(devices.empty());
    const std::string name = devices.front().substr(0, devices.front().find(' '));
    std::string upper = name;
    for (char& c : upper)
        c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    gpu::ContextOptions options;
    options.deviceName = upper;
    gpu::Context ctx(options);
    EXPECT_EQ(ctx.deviceName().rfind(name, 0), 0u);
}

// A deliberately wrong call must reach the callback: proves the layer is live.
TEST(GpuContext, ValidationLayerReportsMisuse) {
    gpu::ContextOptions options;
    options.validation = true;
    gpu::Context ctx(options);
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = 0; // invalid: size must be greater than 0
    info.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    VkBuffer buffer = VK_NULL_HANDLE;
    testing::internal::CaptureStderr();
    VkResult r = vkCreateBuffer(ctx.device(), &info, nullptr, &buffer);
    testing::internal::GetCapturedStderr();
    if (r == VK_SUCCESS && buffer) vkDestroyBuffer(ctx.device(), buffer, nullptr);
    EXPECT_GT(ctx.validationMessageCount(), 0u);
}

} // namespace cutaway::test

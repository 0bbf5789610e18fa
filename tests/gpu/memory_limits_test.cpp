// Device limits and the memory budget: what does not fit is refused up front
// with an error naming the limit, and the count of memory held is exact.
#include "core/error.hpp"
#include "gpu/check.hpp"
#include "gpu/memory.hpp"
#include "gpu/resources.hpp"
#include "gpu_fixture.hpp"

#include <gtest/gtest.h>
#include <initializer_list>
#include <optional>

namespace cutaway::test {
namespace {

constexpr VkDeviceSize kMiB = 1024 * 1024;

std::string inputError(const std::string& text) {
    try {
        gpu::parseMemorySize(text);
    } catch (const InputError& e) {
        return e.what();
    }
    return {};
}

gpu::Image volumeImage(const gpu::Context& ctx, uint32_t side) {
    return gpu::createImage(ctx, VK_IMAGE_TYPE_3D, VK_FORMAT_R16_UNORM, {side, side, side},
                            VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
}

} // namespace

TEST(MemorySize, ParsesBinaryUnitsWithOrWithoutIB) {
    EXPECT_EQ(gpu::parseMemorySize("512M"), 512 * kMiB);
    EXPECT_EQ(gpu::parseMemorySize("2G"), 2048 * kMiB);
    EXPECT_EQ(gpu::parseMemorySize("1.5GiB"), 1536 * kMiB);
    EXPECT_EQ(gpu::parseMemorySize("64 MiB"), 64 * kMiB);
    EXPECT_EQ(gpu::parseMemorySize("4k"), 4096u);
    EXPECT_EQ(gpu::parseMemorySize("1000000"), 1000000u);
    EXPECT_EQ(gpu::parseMemorySize("300B"), 300u);
    for (const char* bad : {"", "abc", "-1G", "0", "12Q", "nan", "inf", "2 GB extra", "1e30T"}) {
        const std::string message = inputError(bad);
        EXPECT_NE(message.find("expected a size such as 512M"), std::string::npos)
            << '"' << bad << "\": " << message;
    }
}

TEST(MemorySize, FormatsWithBinaryUnits) {
    EXPECT_EQ(gpu::formatBytes(12), "12 B");
    EXPECT_EQ(gpu::formatBytes(1536), "1.50 KiB");
    EXPECT_EQ(gpu::formatBytes(512 * kMiB), "512.0 MiB");
    EXPECT_EQ(gpu::formatBytes(3 * 1024 * kMiB), "3.00 GiB");
}

TEST(MemoryLimitsCheck, EachLimitIsNamed) {
    gpu::MemoryLimits limits;
    limits.maxAllocation = 1024 * kMiB;
    limits.heap = 2048 * kMiB;
    limits.budget = limits.heap;
    EXPECT_EQ(gpu::allocationProblem(1024 * kMiB, 1000 * kMiB, limits), "");
    EXPECT_NE(
        gpu::allocationProblem(1025 * kMiB, 0, limits).find("maxMemoryAllocationSize of 1.00 GiB"),
        std::string::npos);
    EXPECT_NE(gpu::allocationProblem(1024 * kMiB, 1025 * kMiB, limits)
                  .find("memory budget of 2.00 GiB (the device-local heap"),
              std::string::npos);
    limits.maxAllocation = 4096 * kMiB; // some devices allow one allocation past a heap
    EXPECT_NE(gpu::allocationProblem(3000 * kMiB, 0, limits).find("largest device-local heap"),
              std::string::npos);
    limits.budget = 100 * kMiB;
    limits.budgetGiven = true;
    EXPECT_NE(gpu::allocationProblem(60 * kMiB, 50 * kMiB, limits)
                  .find("with the 50.0 MiB already held it exceeds the memory budget of 100.0 MiB "
                        "(--memory-budget)"),
              std::string::npos);
    EXPECT_EQ(gpu::allocationProblem(50 * kMiB, 50 * kMiB, limits), "");
}

namespace {

constexpr VkMemoryPropertyFlags kLocal = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
constexpr VkMemoryPropertyFlags kHost =
    VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
constexpr VkMemoryPropertyFlags kCached = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;

VkPhysicalDeviceMemoryProperties memoryTypes(std::initializer_list<VkMemoryPropertyFlags> types) {
    VkPhysicalDeviceMemoryProperties memory{};
    for (const VkMemoryPropertyFlags flags : types)
        memory.memoryTypes[memory.memoryTypeCount++].propertyFlags = flags;
    return memory;
}

// How cutaway picks a type for a buffer the host writes and one it reads back.
struct BufferTypes {
    std::optional<uint32_t> write, read;
};

BufferTypes bufferTypes(const VkPhysicalDeviceMemoryProperties& memory, uint32_t typeBits) {
    return {gpu::chooseMemoryType(memory, typeBits, kHost),
            gpu::chooseMemoryType(memory, typeBits, kHost, kCached)};
}

} // namespace

// Readbacks go to host-cached memory where a type has it; a discrete GPU lists
// its write-combined host type first, which the host reads uncached.
TEST(MemoryType, ReadbacksPreferHostCachedAndUploadsKeepTheFirstHostType) {
    // A discrete NVIDIA GPU's types (vulkaninfo): none, device-local,
    // host-visible write-combined, host-visible cached, device-local mapped.
    const auto nvidia = memoryTypes({0, kLocal, kHost, kHost | kCached, kLocal | kHost});
    BufferTypes t = bufferTypes(nvidia, 0x1f);
    EXPECT_EQ(t.write, 2u);
    EXPECT_EQ(t.read, 3u);
    // A buffer that cannot live in the cached type falls back to the first host type.
    t = bufferTypes(nvidia, 0x17);
    EXPECT_EQ(t.read, 2u);
    // An AMD GPU's: the mapped device-local type before the cached one.
    const auto amd = memoryTypes({kLocal, kHost, kLocal | kHost, kHost | kCached});
    t = bufferTypes(amd, 0xf);
    EXPECT_EQ(t.write, 1u);
    EXPECT_EQ(t.read, 3u);
    // lavapipe: one type with every flag.
    const auto lavapipe = memoryTypes({kLocal | kHost | kCached});
    t = bufferTypes(lavapipe, 0x1);
    EXPECT_EQ(t.write, 0u);
    EXPECT_EQ(t.read, 0u);
    // No host-visible type the buffer may use: none, for either.
    t = bufferTypes(nvidia, 0x3);
    EXPECT_FALSE(t.write);
    EXPECT_FALSE(t.read);
    // A cached type that is not coherent is never taken (nothing invalidates it).
    const auto incoherent = memoryTypes({kLocal, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | kCached});
    EXPECT_FALSE(bufferTypes(incoherent, 0x3).read);
}

TEST_F(GpuTest, MemoryInUseCountsEveryAllocationAndReturnsToZero) {
    EXPECT_EQ(ctx().memoryInUse(), 0u);
    {
        gpu::Image a = volumeImage(ctx(), 32);
        const VkDeviceSize one = ctx().memoryInUse();
        EXPECT_GE(one, 32u * 32u * 32u * 2u);
        gpu::Buffer b = gpu::createBuffer(ctx(), kMiB, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                          gpu::HostAccess::Write);
        EXPECT_GE(ctx().memoryInUse(), one + kMiB);
        gpu::Image moved = std::move(a); // moving does not count twice
        EXPECT_GE(ctx().memoryInUse(), one + kMiB);
        EXPECT_LT(ctx().memoryInUse(), 2 * one + kMiB);
        EXPECT_EQ(ctx().memoryPeak(), ctx().memoryInUse());
    }
    EXPECT_EQ(ctx().memoryInUse(), 0u);
    EXPECT_GE(ctx().memoryPeak(), kMiB); // the peak stays until reset
    ctx().resetMemoryPeak();
    EXPECT_EQ(ctx().memoryPeak(), 0u);
}

TEST(GpuMemoryBudget, AnImagePastTheBudgetIsRefusedNamingItAndWhatItWas) {
    gpu::ContextOptions options;
    options.validation = true;
    options.memoryBudget = 3 * kMiB;
    gpu::Context ctx(options);
    EXPECT_TRUE(ctx.memoryLimits().budgetGiven);
    gpu::Image small = volumeImage(ctx, 64); // 0.5 MiB
    try {
        volumeImage(ctx, 128); // 4 MiB
        FAIL() << "expected a ResourceError";
    } catch (const ResourceError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("a 3D image of 128x128x128 R16_UNORM"), std::string::npos) << what;
        EXPECT_NE(what.find("memory budget of 3.00 MiB (--memory-budget)"), std::string::npos)
            << what;
    }
    EXPECT_LT(ctx.memoryInUse(), kMiB) << "the refused image's memory is counted";
    EXPECT_EQ(ctx.validationMessageCount(), 0u);
}

TEST_F(GpuTest, AVolumePastMaxImageDimension3DIsRefusedNamingTheLimit) {
    const uint32_t limit = ctx().properties().limits.maxImageDimension3D;
    try {
        gpu::createImage(ctx(), VK_IMAGE_TYPE_3D, VK_FORMAT_R16_UNORM, {limit + 1, 2, 2},
                         VK_IMAGE_USAGE_SAMPLED_BIT);
        FAIL() << "expected a ResourceError";
    } catch (const ResourceError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("maxImageDimension3D of " + std::to_string(limit)), std::string::npos)
            << what;
        EXPECT_NE(what.find(std::to_string(limit + 1) + "x2x2"), std::string::npos) << what;
    }
    EXPECT_EQ(ctx().memoryInUse(), 0u);
}

} // namespace cutaway::test

namespace cutaway::test {

TEST(VulkanErrors, OutOfMemoryAndDeviceLossStopTheRunWithAClearMessage) {
    // ResourceError: a sequence stops there (the next frames would fail alike).
    const auto message = [](VkResult result) {
        try {
            gpu::throwVkError(result, "vkQueueSubmit(...)", "slice_renderer.cpp", 42);
        } catch (const ResourceError& e) {
            return std::string("resource: ") + e.what();
        } catch (const RuntimeError& e) {
            return std::string("runtime: ") + e.what();
        }
        return std::string();
    };
    const std::string lost = message(VK_ERROR_DEVICE_LOST);
    EXPECT_NE(lost.find("resource: vkQueueSubmit(...) failed at slice_renderer.cpp:42: "
                        "VK_ERROR_DEVICE_LOST (the device was lost"),
              std::string::npos)
        << lost;
    EXPECT_NE(message(VK_ERROR_OUT_OF_DEVICE_MEMORY).find("resource: "), std::string::npos);
    EXPECT_NE(message(VK_ERROR_OUT_OF_HOST_MEMORY).find("out of memory"), std::string::npos);
    EXPECT_NE(message(VK_ERROR_FORMAT_NOT_SUPPORTED).find("runtime: "), std::string::npos);
}

} // namespace cutaway::test

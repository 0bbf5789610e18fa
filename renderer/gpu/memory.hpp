#pragma once
// Device memory: the limits an allocation must respect, and an owner that
// keeps the context's count of memory in use.
//
// Every buffer and image cutaway creates has one dedicated allocation
// (gpu/resources.hpp), made through Context::allocate(), which refuses, with
// an error naming the limit, an allocation that
//  - is larger than the device's maxMemoryAllocationSize,
//  - is larger than the device's largest device-local heap, or
//  - would bring the memory cutaway holds past the memory budget
//    (--memory-budget; by default the largest device-local heap).
// Nothing is downsampled or bricked behind the user's back: a volume that
// does not fit is an error that says what it needed and what the limit is.
#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vulkan/vulkan.h>

namespace cutaway::gpu {

struct MemoryLimits {
    VkDeviceSize maxAllocation = 0; ///< maxMemoryAllocationSize
    VkDeviceSize heap = 0;          ///< the largest device-local heap
    VkDeviceSize budget = 0;        ///< what cutaway may hold at once
    bool budgetGiven = false;       ///< budget came from --memory-budget, not the heap
};

/// The device's limits; budget = `budgetOption` when non-zero, else the heap.
MemoryLimits queryMemoryLimits(VkPhysicalDevice device, VkDeviceSize budgetOption);

/// Why `size` more bytes cannot be allocated while `inUse` are held, naming
/// the limit; empty when they can.
std::string allocationProblem(VkDeviceSize size, VkDeviceSize inUse, const MemoryLimits& limits);

/// The memory type for an allocation: the first type allowed by `typeBits`
/// with all of `required` and all of `preferred`, else the first with
/// `required`; none if no type has it. Buffers the host reads back prefer
/// HOST_CACHED: discrete GPUs list a write-combined host type first, and the
/// host reads such memory uncached, word by word from RAM.
std::optional<uint32_t> chooseMemoryType(const VkPhysicalDeviceMemoryProperties& memory,
                                         uint32_t typeBits, VkMemoryPropertyFlags required,
                                         VkMemoryPropertyFlags preferred = 0);

/// "512M", "2G", "1.5GiB", "64 MiB", "1000000" (bytes); K, M, G, T are binary
/// (1024-based) with or without "iB". Throws InputError saying what it expected.
VkDeviceSize parseMemorySize(const std::string& text);

/// "1.50 GiB", "512.0 MiB", "12 B".
std::string formatBytes(VkDeviceSize bytes);

/// One vkAllocateMemory result; frees it and gives its bytes back to the
/// context's count when destroyed. Move-only.
class DeviceMemory {
public:
    DeviceMemory() = default;
    DeviceMemory(VkDevice device, VkDeviceMemory memory, VkDeviceSize size,
                 std::atomic<VkDeviceSize>* inUse) noexcept
        : m_device(device), m_memory(memory), m_size(size), m_inUse(inUse) {}
    ~DeviceMemory() { reset(); }
    DeviceMemory(const DeviceMemory&) = delete;
    DeviceMemory& operator=(const DeviceMemory&) = delete;
    DeviceMemory(DeviceMemory&& other) noexcept { *this = std::move(other); }
    DeviceMemory& operator=(DeviceMemory&& other) noexcept;

    VkDeviceMemory get() const { return m_memory; }
    VkDeviceSize size() const { return m_size; }
    void reset() noexcept;

private:
    VkDevice m_device = VK_NULL_HANDLE;
    VkDeviceMemory m_memory = VK_NULL_HANDLE;
    VkDeviceSize m_size = 0;
    std::atomic<VkDeviceSize>* m_inUse = nullptr;
};

} // namespace cutaway::gpu

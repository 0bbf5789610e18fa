#include "gpu/memory.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

namespace cutaway::gpu {

MemoryLimits queryMemoryLimits(VkPhysicalDevice device, VkDeviceSize budgetOption) {
    VkPhysicalDeviceVulkan11Properties p11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties.pNext = &p11;
    vkGetPhysicalDeviceProperties2(device, &properties);
    VkPhysicalDeviceMemoryProperties memory;
    vkGetPhysicalDeviceMemoryProperties(device, &memory);

    MemoryLimits limits;
    limits.maxAllocation = p11.maxMemoryAllocationSize;
    for (uint32_t i = 0; i < memory.memoryHeapCount; ++i)
        if (memory.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
            limits.heap = std::max(limits.heap, memory.memoryHeaps[i].size);
    limits.budgetGiven = budgetOption != 0;
    limits.budget = limits.budgetGiven ? budgetOption : limits.heap;
    return limits;
}

std::optional<uint32_t> chooseMemoryType(const VkPhysicalDeviceMemoryProperties& memory,
                                         uint32_t typeBits, VkMemoryPropertyFlags required,
                                         VkMemoryPropertyFlags preferred) {
    const auto first = [&](VkMemoryPropertyFlags flags) -> std::optional<uint32_t> {
        for (uint32_t i = 0; i < memory.memoryTypeCount; ++i)
            if ((typeBits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & flags) == flags)
                return i;
        return std::nullopt;
    };
    if (preferred != 0)
        if (const auto both = first(required | preferred)) return both;
    return first(required);
}

std::string allocationProblem(VkDeviceSize size, VkDeviceSize inUse, const MemoryLimits& limits) {
    if (limits.maxAllocation != 0 && size > limits.maxAllocation)
        return "it is larger than the device's maxMemoryAllocationSize of " +
               formatBytes(limits.maxAllocation);
    if (limits.heap != 0 && size > limits.heap)
        return "it is larger than the device's largest device-local heap, " +
               formatBytes(limits.heap);
    if (limits.budget != 0 && inUse + size > limits.budget)
        return "with the " + formatBytes(inUse) + " already held it exceeds the memory budget of " +
               formatBytes(limits.budget) +
               (limits.budgetGiven ? " (--memory-budget)"
                                   : " (the device-local heap; --memory-budget sets another)");
    return {};
}

VkDeviceSize parseMemorySize(const std::string& text) {
    const std::string expected = "expected a size such as 512M, 2G or 1.5GiB, got \"" + text + "\"";
    std::size_t used = 0;
    double number = 0.0;
    try {
        number = std::stod(text, &used);
    } catch (const std::exception&) {
        throw InputError(expected);
    }
    std::string unit = text.substr(used);
    unit.erase(std::remove_if(unit.begin(), unit.end(), [](unsigned char c) { return c == ' '; }),
               unit.end());
    for (char& c : unit)
        c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (unit.size() == 3 && unit.substr(1) == "IB") unit.resize(1);
    if (unit.size() == 2 && unit[1] == 'B') unit.resize(1);
    static const std::string kUnits = "BKMGT";
    const std::size_t power = unit.empty() ? 0 : kUnits.find(unit);
    if (unit.size() > 1 || power == std::string::npos || !std::isfinite(number) || number <= 0.0)
        throw InputError(expected);
    const double bytes = number * std::pow(1024.0, static_cast<double>(power));
    if (bytes < 1.0 || bytes > 0x1p60) throw InputError(expected + " (between 1 byte and 1 EiB)");
    return static_cast<VkDeviceSize>(bytes);
}

std::string formatBytes(VkDeviceSize bytes) {
    static const char* kUnits[] = {"B", "KiB", "MiB", "GiB", "TiB"};
    double value = static_cast<double>(bytes);
    int unit = 0;
    while (value >= 1024.0 && unit < 4) {
        value /= 1024.0;
        ++unit;
    }
    char text[32];
    if (unit == 0)
        std::snprintf(text, sizeof text, "%llu B", static_cast<unsigned long long>(bytes));
    else
        std::snprintf(text, sizeof text, value < 10.0 ? "%.2f %s" : "%.1f %s", value, kUnits[unit]);
    return text;
}

DeviceMemory& DeviceMemory::operator=(DeviceMemory&& other) noexcept {
    if (this != &other) {
        reset();
        m_device = other.m_device;
        m_memory = std::exchange(other.m_memory, VK_NULL_HANDLE);
        m_size = std::exchange(other.m_size, 0);
        m_inUse = std::exchange(other.m_inUse, nullptr);
    }
    return *this;
}

void DeviceMemory::reset() noexcept {
    if (m_memory != VK_NULL_HANDLE) {
        vkFreeMemory(m_device, m_memory, nullptr);
        if (m_inUse != nullptr) m_inUse->fetch_sub(m_size);
    }
    m_memory = VK_NULL_HANDLE;
    m_size = 0;
}

} // namespace cutaway::gpu

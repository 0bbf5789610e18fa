#pragma once
// A headless Vulkan 1.3 context: instance, one device, one queue that does
// graphics and compute, a command pool. No surface, no swapchain.
//
// Device choice: the first device that can run cutaway, preferring discrete
// GPUs, then integrated, virtual, and last CPU implementations (lavapipe).
// ContextOptions::deviceName picks by case-insensitive substring instead.
// When nothing fits, the error lists every device with the reason it was
// rejected.
//
// Validation: with the Khronos validation layer on (ContextOptions::validation,
// or CUTAWAY_VALIDATION=1 in the environment), every warning or error message
// is printed to stderr and counted; tests fail when the count is not zero.
#include "gpu/device_tuning.hpp"
#include "gpu/handle.hpp"
#include "gpu/memory.hpp"

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>
#include <vulkan/vulkan.h>

namespace cutaway::gpu {

struct ContextOptions {
    bool validation = false;       ///< also switched on by CUTAWAY_VALIDATION=1
    std::string deviceName;        ///< substring of the device name; empty = best device
    VkDeviceSize memoryBudget = 0; ///< bytes cutaway may hold at once; 0 = the device-local heap
    /// The paths to take on this device instead of its own profile (tests:
    /// the GPU profile on lavapipe), less what the device cannot run.
    std::optional<DeviceTuning> tuning;
};

/// A descriptor set layout as it was made (gpu::createSetLayout), for tests
/// that check what a device's pipelines bind.
struct SetLayoutRecord {
    std::string name;
    std::vector<VkDescriptorSetLayoutBinding> bindings;
};

/// What the device supports among the formats cutaway uses.
struct DeviceFormats {
    VkFormat color = VK_FORMAT_UNDEFINED;        ///< accumulation target: RGBA32F, else RGBA16F
    VkFormat depthStencil = VK_FORMAT_UNDEFINED; ///< D32S8, else D24S8
    /// R8_UNORM and R16_UNORM can be storage images: the volume's values can
    /// be read with imageLoad as well as sampled (bake/volume_upload.hpp).
    bool storageValues = false;
};

class Context {
public:
    explicit Context(const ContextOptions& options = {});
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const { return m_instance; }
    VkPhysicalDevice physicalDevice() const { return m_physicalDevice; }
    VkDevice device() const { return m_device; }
    VkQueue queue() const { return m_queue; }
    uint32_t queueFamily() const { return m_queueFamily; }
    const VkPhysicalDeviceProperties& properties() const { return m_properties; }
    const DeviceFormats& formats() const { return m_formats; }
    std::string deviceName() const { return m_properties.deviceName; }
    /// Compute shaders can use subgroup ballots (GL_KHR_shader_subgroup_ballot).
    bool computeBallots() const { return m_computeBallots; }
    /// The paths this device takes (gpu/device_tuning.hpp): its profile, or
    /// ContextOptions::tuning.
    const DeviceTuning& tuning() const { return m_tuning; }
    /// `wanted` without what this device cannot run.
    DeviceTuning supported(const DeviceTuning& wanted) const {
        return supportedTuning(wanted, m_formats.storageValues, m_computeBallots);
    }
    bool validationEnabled() const { return m_validation; }

    /// Index of a memory type allowed by `typeBits` that has `required`, one
    /// that also has `preferred` if there is one (chooseMemoryType); throws if none.
    uint32_t memoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                        VkMemoryPropertyFlags preferred = 0) const;

    const MemoryLimits& memoryLimits() const { return m_memoryLimits; }
    /// Bytes of device memory held now by what allocate() returned.
    VkDeviceSize memoryInUse() const { return m_memoryInUse.load(); }
    /// The most held at once since the context was made or the last reset.
    VkDeviceSize memoryPeak() const { return m_memoryPeak.load(); }
    void resetMemoryPeak() const { m_memoryPeak.store(memoryInUse()); }
    /// Memory for `req` with `required` (and `preferred` where a type has
    /// both). Throws RuntimeError naming `what` (e.g. "a 3D image of
    /// 256x256x256 R16_UNORM") and the limit when it exceeds one
    /// (gpu/memory.hpp) or the device is out of memory.
    DeviceMemory allocate(const VkMemoryRequirements& req, VkMemoryPropertyFlags required,
                          const std::string& what, VkMemoryPropertyFlags preferred = 0) const;

    /// Records commands into a fresh primary command buffer, submits it and
    /// waits for it to finish. Safe to call from several threads: the calls
    /// take turns.
    void submitAndWait(const std::function<void(VkCommandBuffer)>& record) const;

    /// Validation messages (warnings and errors) seen so far.
    std::vector<std::string> validationMessages() const;
    std::size_t validationMessageCount() const;

    /// Every descriptor set layout made so far on this device, by name, where
    /// validation is on (as in every test); none otherwise.
    std::vector<SetLayoutRecord> setLayouts() const;
    /// Called by gpu::createSetLayout.
    void recordSetLayout(SetLayoutRecord record) const;

    /// Called by the debug messenger; public only for the C callback.
    void onValidationMessage(const std::string& message);

private:
    void release() noexcept;

    bool m_validation = false;
    VkInstance m_instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT m_messenger = VK_NULL_HANDLE;
    VkPhysicalDevice m_physicalDevice = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties m_properties{};
    bool m_computeBallots = false;
    DeviceTuning m_tuning;
    VkPhysicalDeviceMemoryProperties m_memory{};
    MemoryLimits m_memoryLimits;
    mutable std::atomic<VkDeviceSize> m_memoryInUse{0};
    mutable std::atomic<VkDeviceSize> m_memoryPeak{0};
    DeviceFormats m_formats;
    uint32_t m_queueFamily = 0;
    VkDevice m_device = VK_NULL_HANDLE;
    VkQueue m_queue = VK_NULL_HANDLE;
    CommandPoolHandle m_commandPool;
    mutable std::mutex m_submitMutex; ///< the pool and the queue, one submission at a time
    mutable std::mutex m_messagesMutex;
    std::vector<std::string> m_messages;
    mutable std::vector<SetLayoutRecord> m_setLayouts; ///< guarded by m_messagesMutex
};

/// Names and types of the Vulkan devices present, each with its limits on
/// volume size (maxImageDimension3D, maxMemoryAllocationSize, heap).
std::vector<std::string> listDevices();

} // namespace cutaway::gpu

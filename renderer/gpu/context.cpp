#include "gpu/context.hpp"

#include "core/error.hpp"
#include "gpu/check.hpp"
#include "gpu/device_select.hpp"

#include <cstdlib>
#include <cstring>
#include <iostream>

namespace cutaway::gpu {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool envFlag(const char* name) {
    const char* v = std::getenv(name);
    return v && *v && std::strcmp(v, "0") != 0;
}

VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                             VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data,
                                             void* user) {
    const char* level =
        (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning";
    std::string message = std::string("vulkan validation ") + level + ": " +
                          (data && data->pMessage ? data->pMessage : "(no text)");
    static_cast<Context*>(user)->onValidationMessage(message);
    return VK_FALSE;
}

bool layerAvailable(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    for (const auto& l : layers)
        if (std::strcmp(l.layerName, name) == 0) return true;
    return false;
}

VkInstance createInstance(bool validation, Context* context, VkDebugUtilsMessengerEXT* messenger) {
    if (validation && !layerAvailable(kValidationLayer))
        throw RuntimeError("validation requested but VK_LAYER_KHRONOS_validation is not "
                           "installed: install vulkan-validationlayers");

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "cutaway";
    app.applicationVersion = VK_MAKE_VERSION(0, 1, 0);
    app.pEngineName = "cutaway";
    app.apiVersion = VK_API_VERSION_1_3;

    VkDebugUtilsMessengerCreateInfoEXT debugInfo{
        VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    debugInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    debugInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    debugInfo.pfnUserCallback = debugCallback;
    debugInfo.pUserData = context;

    const char* layers[] = {kValidationLayer};
    const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    if (validation) {
        info.enabledLayerCount = 1;
        info.ppEnabledLayerNames = layers;
        info.enabledExtensionCount = 1;
        info.ppEnabledExtensionNames = extensions;
        info.pNext = &debugInfo; // also catches messages from instance creation itself
    }
    VkInstance instance = VK_NULL_HANDLE;
    VkResult result = vkCreateInstance(&info, nullptr, &instance);
    if (result == VK_ERROR_INCOMPATIBLE_DRIVER)
        throw RuntimeError("no Vulkan device: install mesa-vulkan-drivers (lavapipe, the CPU "
                           "implementation) or a GPU driver with Vulkan 1.3");
    VK_CHECK(result);

    if (validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
        if (!create || create(instance, &debugInfo, nullptr, messenger) != VK_SUCCESS) {
            vkDestroyInstance(instance, nullptr);
            throw RuntimeError("cannot install the validation message callback");
        }
    }
    return instance;
}

} // namespace

Context::Context(const ContextOptions& options)
    : m_validation(options.validation || envFlag("CUTAWAY_VALIDATION")) {
    m_instance = createInstance(m_validation, this, &m_messenger);
    try {
        DeviceChoice choice = chooseDevice(m_instance, options.deviceName);
        m_physicalDevice = choice.device;
        m_queueFamily = choice.queueFamily;
        m_formats = choice.formats;
        vkGetPhysicalDeviceProperties(m_physicalDevice, &m_properties);
        m_computeBallots = hasComputeBallots(m_physicalDevice);
        m_tuning = options.tuning ? supported(*options.tuning) : profileOf(m_physicalDevice);
        vkGetPhysicalDeviceMemoryProperties(m_physicalDevice, &m_memory);
        m_memoryLimits = queryMemoryLimits(m_physicalDevice, options.memoryBudget);

        float priority = 1.0f;
        VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        queueInfo.queueFamilyIndex = m_queueFamily;
        queueInfo.queueCount = 1;
        queueInfo.pQueuePriorities = &priority;

        VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
        f13.dynamicRendering = VK_TRUE;
        f13.synchronization2 = VK_TRUE;
        VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f13, {}};
        features.features.shaderStorageImageExtendedFormats = VK_TRUE; // r16f feature fields
        VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        info.pNext = &features;
        info.queueCreateInfoCount = 1;
        info.pQueueCreateInfos = &queueInfo;
        VK_CHECK(vkCreateDevice(m_physicalDevice, &info, nullptr, &m_device));
        vkGetDeviceQueue(m_device, m_queueFamily, 0, &m_queue);

        VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
        poolInfo.queueFamilyIndex = m_queueFamily;
        VkCommandPool pool = VK_NULL_HANDLE;
        VK_CHECK(vkCreateCommandPool(m_device, &poolInfo, nullptr, &pool));
        m_commandPool = CommandPoolHandle(m_device, pool);
    } catch (...) {
        release(); // what was created so far, in reverse
        throw;
    }
}

Context::~Context() {
    release();
}

void Context::release() noexcept {
    if (m_device) vkDeviceWaitIdle(m_device);
    m_commandPool.reset();
    if (m_device) vkDestroyDevice(m_device, nullptr);
    m_device = VK_NULL_HANDLE;
    if (m_messenger) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(m_instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(m_instance, m_messenger, nullptr);
        m_messenger = VK_NULL_HANDLE;
    }
    if (m_instance) vkDestroyInstance(m_instance, nullptr);
    m_instance = VK_NULL_HANDLE;
}

uint32_t Context::memoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                             VkMemoryPropertyFlags preferred) const {
    if (const auto type = chooseMemoryType(m_memory, typeBits, required, preferred)) return *type;
    throw RuntimeError("no Vulkan memory type with the needed properties on " + deviceName());
}

DeviceMemory Context::allocate(const VkMemoryRequirements& req, VkMemoryPropertyFlags required,
                               const std::string& what, VkMemoryPropertyFlags preferred) const {
    const auto refuse = [&](const std::string& why) {
        return ResourceError("cannot allocate " + formatBytes(req.size) + " of device memory for " +
                             what + " on " + deviceName() + ": " + why);
    };
    const std::string problem = allocationProblem(req.size, memoryInUse(), m_memoryLimits);
    if (!problem.empty()) throw refuse(problem);
    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    info.allocationSize = req.size;
    info.memoryTypeIndex = memoryType(req.memoryTypeBits, required, preferred);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    const VkResult result = vkAllocateMemory(m_device, &info, nullptr, &memory);
    if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY)
        throw refuse(std::string("the device is out of memory (") + resultName(result) + ") with " +
                     formatBytes(memoryInUse()) + " held; --memory-budget below that would " +
                     "name the limit up front");
    VK_CHECK(result);
    const VkDeviceSize held = m_memoryInUse.fetch_add(req.size) + req.size;
    VkDeviceSize peak = m_memoryPeak.load();
    while (held > peak && !m_memoryPeak.compare_exchange_weak(peak, held)) {
    }
    return DeviceMemory(m_device, memory, req.size, &m_memoryInUse);
}

void Context::submitAndWait(const std::function<void(VkCommandBuffer)>& record) const {
    // The pool (allocation and recording) and the queue are externally
    // synchronized objects: one submission at a time.
    const std::lock_guard lock(m_submitMutex);
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = m_commandPool.get();
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VK_CHECK(vkAllocateCommandBuffers(m_device, &alloc, &cmd));
    struct Free { // returns the command buffer to the pool on every path
        VkDevice device;
        VkCommandPool pool;
        VkCommandBuffer cmd;
        ~Free() { vkFreeCommandBuffers(device, pool, 1, &cmd); }
    } freeLater{m_device, m_commandPool.get(), cmd};

    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    record(cmd);
    VK_CHECK(vkEndCommandBuffer(cmd));

    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence rawFence = VK_NULL_HANDLE;
    VK_CHECK(vkCreateFence(m_device, &fenceInfo, nullptr, &rawFence));
    FenceHandle fence(m_device, rawFence);
    VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmdInfo.commandBuffer = cmd;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmdInfo;
    VK_CHECK(vkQueueSubmit2(m_queue, 1, &submit, fence.get()));
    VK_CHECK(vkWaitForFences(m_device, 1, &rawFence, VK_TRUE, UINT64_MAX));
}

void Context::onValidationMessage(const std::string& message) {
    std::lock_guard lock(m_messagesMutex);
    std::cerr << message << "\n";
    m_messages.push_back(message);
}

std::vector<std::string> Context::validationMessages() const {
    std::lock_guard lock(m_messagesMutex);
    return m_messages;
}

std::size_t Context::validationMessageCount() const {
    std::lock_guard lock(m_messagesMutex);
    return m_messages.size();
}

std::vector<SetLayoutRecord> Context::setLayouts() const {
    std::lock_guard lock(m_messagesMutex);
    return m_setLayouts;
}

void Context::recordSetLayout(SetLayoutRecord record) const {
    if (!m_validation) return; // a record for checks, which run with validation on
    std::lock_guard lock(m_messagesMutex);
    m_setLayouts.push_back(std::move(record));
}

std::vector<std::string> listDevices() {
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkInstance instance = createInstance(false, nullptr, &messenger);
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(instance, &count, devices.data());
    std::vector<std::string> names;
    for (VkPhysicalDevice d : devices) {
        VkPhysicalDeviceProperties properties;
        vkGetPhysicalDeviceProperties(d, &properties);
        const MemoryLimits memory = queryMemoryLimits(d, 0);
        names.push_back(describeDevice(d) + "\n  maxImageDimension3D " +
                        std::to_string(properties.limits.maxImageDimension3D) +
                        ", maxMemoryAllocationSize " + formatBytes(memory.maxAllocation) +
                        ", device-local heap " + formatBytes(memory.heap) + "\n  tuning " +
                        tuningName(profileOf(d)));
    }
    vkDestroyInstance(instance, nullptr);
    return names;
}

} // namespace cutaway::gpu

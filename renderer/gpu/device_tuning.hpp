#pragma once
// What cutaway does differently on one device: the paths that pay on CPU
// implementations of Vulkan (lavapipe) and cost a GPU, decided once per
// device, as Granite's ImplementationQuirks. The Context fills the record
// when it picks the device (ContextOptions::tuning overrides it, for tests);
// the volume upload, the gradient bake and the renderer take it at
// construction, and each path costs nothing where the record leaves it off:
// no storage usage, no GENERAL layout, no stand-in images, no bindings.
// docs/design/cpu-device-paths.md gives the measurements behind each.
#include <vulkan/vulkan.h>

namespace cutaway::gpu {

struct DeviceTuning {
    /// The volume's values, and surface alignment's distance field, read
    /// with imageLoad and filtered in the shaders instead of sampled: on
    /// lavapipe a sampled fetch of an 8- or 16-bit texture is a call that
    /// gathers its texels one by one, imageLoad an inline load. Costs the
    /// value texture storage usage and the GENERAL layout. Needs R8 and R16
    /// storage images (DeviceFormats::storageValues).
    bool storageValues = false;
    /// Gradients baked in bricks of 4^3 texels and filtered in the shaders,
    /// so a sample's eight texels share cache lines on a CPU. A GPU's
    /// sampler filters the linear layout for free.
    bool brickedGradients = false;
    /// The ray caster's lanes that step over transparent samples stop for a
    /// pass of shading as soon as one lane waits: a CPU runs a subgroup's
    /// lanes in lock-step and pays for every pass. Needs subgroup ballots in
    /// compute shaders.
    bool yieldLanes = false;

    /// Whether shaders declare the storage-image bindings of the first two
    /// (shaders/shared/bindings.h, CW_STORAGE_PATHS).
    bool storageImages() const { return storageValues || brickedGradients; }
    bool operator==(const DeviceTuning&) const = default;
};

/// What a device can take: `wanted` without the paths it cannot run.
DeviceTuning supportedTuning(DeviceTuning wanted, bool storageFormats, bool computeBallots);

/// The profile of a device of `type`: every path it can run on a CPU
/// implementation, none on a GPU.
DeviceTuning tuningFor(VkPhysicalDeviceType type, bool storageFormats, bool computeBallots);

/// A GPU's profile: none of the CPU paths.
inline constexpr DeviceTuning kGpuTuning{};
/// A CPU implementation's profile, before what the device can take.
inline constexpr DeviceTuning kCpuTuning{true, true, true};

/// The profile's name for logs and `cutaway devices`: "gpu", "cpu" or "custom".
const char* tuningName(const DeviceTuning& tuning);

} // namespace cutaway::gpu

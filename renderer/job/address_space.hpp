#pragma once
// Rendering under an address-space limit (RLIMIT_AS, `ulimit -v`, as HPC
// schedulers set): past it, allocations fail wherever they happen, and
// inside the Vulkan driver (lavapipe compiling a pipeline with LLVM) that
// was a segmentation fault. What a frame needs is checked against the limit
// before the device is made (the driver and the image) and again once the
// volume is known, before it is uploaded and the pipelines are made; a
// frame that needs more fails with exit code 1 and a message naming the
// limit. The figures are estimates measured on lavapipe (README, "Memory
// limits"): a GPU driver's own needs differ, and what it does past the
// limit remains the driver's.
#include "scene/scene.hpp"
#include "volume/volume.hpp"

#include <cstdint>
#include <optional>

namespace cutaway::job {

/// Bytes of address space a frame needs, by what needs them.
struct AddressSpaceNeed {
    std::uint64_t driver = 0; ///< Vulkan, lavapipe's threads and its pipelines
    std::uint64_t volume = 0; ///< the volume, its labels, their textures and bakes
    std::uint64_t image = 0;  ///< render targets, readback, the files being written
    unsigned threads = 0;     ///< lavapipe's rasterizer threads counted in `driver`
    std::uint64_t total() const { return driver + volume + image; }
};

/// The need of `frame` (its size, its aligned operators) with `scan` and
/// `labels` when they are known (null: the driver and the image alone).
AddressSpaceNeed addressSpaceNeed(const Scene& frame, const Volume* scan = nullptr,
                                  const Volume* labels = nullptr);

/// The process's address-space limit in bytes (the soft RLIMIT_AS), or
/// nullopt when there is none.
std::optional<std::uint64_t> addressSpaceLimit();

/// Throws ResourceError "address-space limit (ulimit -v) of N KiB is below
/// the ~M MiB this frame needs (...)" when the limit is below `need`.
void checkAddressSpace(const AddressSpaceNeed& need);

} // namespace cutaway::job

#include "job/address_space.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <cstdlib>
#include <string>
#include <string_view>
#include <sys/resource.h>
#include <thread>

namespace cutaway::job {
namespace {

constexpr std::uint64_t kMiB = std::uint64_t{1} << 20;

// Measured on lavapipe (LLVM 15, shared malloc arenas: core/process_memory.hpp)
// as the smallest limit under which a frame of a 16^3 volume rendered three
// times out of three: 296 MiB with 1 rasterizer thread, 312 with 2, 396
// with 4, 463 with 8, 589 with 16. kDriverBase + kPerThread * threads lies
// above each once kMargin is applied.
constexpr std::uint64_t kDriverBase = 300 * kMiB;
constexpr std::uint64_t kPerThread = 20 * kMiB;
// The Khronos validation layer (CUTAWAY_VALIDATION=1): 396 MiB with 2 threads.
constexpr std::uint64_t kValidationLayer = 90 * kMiB;
// Per voxel beyond its own bytes: the value texture, the gradients, staging
// and what reading a file holds for a moment (measured: 10.5 bytes per voxel
// of a uint8 256^3 phantom, 11.3 of ct_head read from gzip); an aligned
// operator's feature field and its bake's masks add kFieldBytesPerVoxel.
constexpr std::uint64_t kTextureBytesPerVoxel = 10;
constexpr std::uint64_t kFieldBytesPerVoxel = 4;
// Per pixel: the targets, the readback, the image and the files being
// written (measured: 56 bytes per pixel between 1024^2 and 2048^2 frames).
constexpr std::uint64_t kBytesPerPixel = 80;
constexpr double kMargin = 1.15;
// lavapipe's most rasterizer threads.
constexpr unsigned kMostThreads = 32;

// lavapipe's rasterizer threads: LP_NUM_THREADS, else one per core.
unsigned lavapipeThreads() {
    unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    if (const char* set = std::getenv("LP_NUM_THREADS")) {
        char* end = nullptr;
        const unsigned long n = std::strtoul(set, &end, 10);
        if (end != set && *end == '\0') threads = static_cast<unsigned>(std::min(n, 1000ul));
    }
    return std::min(threads, kMostThreads);
}

std::uint64_t withMargin(std::uint64_t bytes) {
    return static_cast<std::uint64_t>(static_cast<double>(bytes) * kMargin);
}

std::uint64_t volumeBytes(const Scene& frame, const Volume& scan, const Volume* labels) {
    const std::uint64_t voxels = scan.voxelCount();
    std::uint64_t bytes = voxels * (voxelSize(scan.type) + kTextureBytesPerVoxel);
    const bool aligned =
        std::any_of(frame.operators.begin(), frame.operators.end(), [](const OperatorSpec& op) {
            return op.alignment.mode != AlignmentMode::Axis;
        });
    if (aligned) bytes += voxels * kFieldBytesPerVoxel;
    if (labels != nullptr && labels != &scan) bytes += voxels * (voxelSize(labels->type) + 1);
    return bytes;
}

std::string mib(std::uint64_t bytes) {
    return std::to_string((bytes + kMiB / 2) / kMiB);
}

} // namespace

AddressSpaceNeed addressSpaceNeed(const Scene& frame, const Volume* scan, const Volume* labels) {
    AddressSpaceNeed need;
    need.threads = lavapipeThreads();
    const char* validation = std::getenv("CUTAWAY_VALIDATION");
    const bool layer = validation != nullptr && *validation != '\0' &&
                       std::string_view(validation) != "0"; // as gpu::Context reads it
    need.driver =
        withMargin(kDriverBase + kPerThread * need.threads + (layer ? kValidationLayer : 0));
    const auto pixels = static_cast<std::uint64_t>(frame.render.width) *
                        static_cast<std::uint64_t>(frame.render.height);
    need.image = withMargin(pixels * kBytesPerPixel);
    if (scan != nullptr) need.volume = withMargin(volumeBytes(frame, *scan, labels));
    return need;
}

std::optional<std::uint64_t> addressSpaceLimit() {
    rlimit limit{};
    if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return std::nullopt;
    return static_cast<std::uint64_t>(limit.rlim_cur);
}

void checkAddressSpace(const AddressSpaceNeed& need) {
    const std::optional<std::uint64_t> limit = addressSpaceLimit();
    if (!limit || *limit >= need.total()) return;
    std::string parts = "the Vulkan driver ~" + mib(need.driver) + " MiB";
    if (need.volume > 0) parts += ", the volume and its textures ~" + mib(need.volume) + " MiB";
    parts += ", the image ~" + mib(need.image) + " MiB, as measured on lavapipe with " +
             std::to_string(need.threads) + " thread(s)";
    throw ResourceError("address-space limit (ulimit -v) of " + std::to_string(*limit >> 10) +
                        " KiB (" + std::to_string(*limit / kMiB) + " MiB) is below the ~" +
                        mib(need.total()) + " MiB this frame needs (" + parts +
                        "); raise the limit, or render a smaller volume or image");
}

} // namespace cutaway::job

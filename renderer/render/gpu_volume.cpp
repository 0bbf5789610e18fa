#include "render/gpu_volume.hpp"

#include <algorithm>
#include <atomic>
#include <glm/gtc/matrix_transform.hpp>

namespace cutaway::render {

glm::dmat4 GpuVolume::worldToTexture() const {
    const glm::dvec3 extent = box.hi - box.lo;
    return glm::scale(glm::dmat4(1.0), 1.0 / extent) * glm::translate(glm::dmat4(1.0), -box.lo);
}

double GpuVolume::smallestSpacing() const {
    return std::min({spacing.x, spacing.y, spacing.z});
}

GpuVolume prepareVolume(const gpu::Context& ctx, const bake::GradientBaker& baker,
                        std::shared_ptr<const Volume> scan, bake::ValueWindow window,
                        std::optional<glm::dvec3> worldLo, std::shared_ptr<const Volume> labels) {
    static std::atomic<std::uint64_t> serials{0};
    const Volume& volume = *scan;
    GpuVolume gv;
    gv.serial = ++serials;
    gv.dims = volume.dims;
    gv.spacing = volume.spacing;
    gv.window = window;
    const glm::dvec3 lo = worldLo.value_or(-0.5 * volume.extent());
    gv.box = Box{lo, lo + volume.extent()};
    gv.values = bake::uploadVolume(ctx, volume, window, baker.tuning().storageValues);
    gv.gradientLayout = bake::gradientLayoutFor(ctx, baker.tuning(), volume.dims);
    gv.gradients = baker.bake(gv.values, volume.spacing, gv.gradientLayout);
    gv.scan = std::move(scan);
    gv.labels = std::move(labels);
    return gv;
}

} // namespace cutaway::render

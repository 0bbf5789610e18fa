#pragma once
// A volume as the renderer samples it: the value texture (uploaded once) and
// its baked gradients, with the geometry that maps world space onto them.
// Made once per sequence; frames only read it.
#include "bake/gradient_bake.hpp"
#include "bake/volume_upload.hpp"
#include "gpu/resources.hpp"
#include "render/camera.hpp"
#include "volume/volume.hpp"

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <optional>

namespace cutaway::render {

struct GpuVolume {
    gpu::Image values;
    gpu::Image gradients;
    bake::GradientLayout gradientLayout = bake::GradientLayout::Linear;
    glm::ivec3 dims{0};
    glm::dvec3 spacing{1.0};
    bake::ValueWindow window;
    Box box; ///< world space: centred on the origin, extent dims * spacing
    /// The volume on the host, kept for what is derived from it per scene:
    /// segment masks of a value range and Otsu thresholds (feature alignment).
    std::shared_ptr<const Volume> scan;
    /// The label volume on the same grid, or null (classification by label,
    /// segment alignment).
    std::shared_ptr<const Volume> labels;
    std::uint64_t serial = 0; ///< unique per prepared volume: what device caches key on

    /// World (mm) -> texture coordinates [0,1]^3.
    glm::dmat4 worldToTexture() const;
    double smallestSpacing() const;
};

/// Uploads `volume` normalized over `window` and bakes its gradients, for
/// the paths of `baker`'s tuning (GradientBaker::tuning). Its box
/// is centred on the world's origin unless `worldLo` places its low corner.
/// `labels`, if any, must be on the volume's grid (see job::loadSceneLabels).
GpuVolume prepareVolume(const gpu::Context& ctx, const bake::GradientBaker& baker,
                        std::shared_ptr<const Volume> volume, bake::ValueWindow window,
                        std::optional<glm::dvec3> worldLo = std::nullopt,
                        std::shared_ptr<const Volume> labels = nullptr);

} // namespace cutaway::render

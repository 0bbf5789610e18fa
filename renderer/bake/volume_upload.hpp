#pragma once
// Uploads a volume as a 3D R16_UNORM texture of the value normalized over a
// window: texel = clamp((value - lo) / (hi - lo), 0, 1). Two bytes per voxel
// whatever the source type, filterable on every Vulkan device.
#include "gpu/context.hpp"
#include "gpu/resources.hpp"
#include "volume/volume.hpp"

#include <glm/glm.hpp>
#include <vector>

namespace cutaway::bake {

struct ValueWindow {
    double lo = 0.0;
    double hi = 1.0;
};

/// Texels as uploaded (x fastest), exposed for the CPU reference in tests.
std::vector<uint16_t> normalizeVolume(const Volume& volume, ValueWindow window);

/// A sampled 3D image in SHADER_READ_ONLY_OPTIMAL, readable by fragment and compute shaders.
gpu::Image uploadVolume(const gpu::Context& ctx, const Volume& volume, ValueWindow window);

} // namespace cutaway::bake

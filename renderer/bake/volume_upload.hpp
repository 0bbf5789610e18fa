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

/// A 0/1 mask (one byte per voxel, x fastest) as an R8_UNORM 3D image that
/// samples 0 or 1, like uploadVolume over the window [0, 1] at an eighth of
/// the work: no conversion, half the bytes.
gpu::Image uploadMask(const gpu::Context& ctx, const std::vector<uint8_t>& mask, glm::ivec3 dims);

} // namespace cutaway::bake

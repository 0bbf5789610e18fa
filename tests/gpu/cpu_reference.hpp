#pragma once
// An independent CPU renderer for tests: for every pixel it intersects the
// pixel's ray with the same view-aligned planes the GPU slices with, samples
// a CPU copy of the volume and its gradients (trilinear, clamp to edge),
// classifies, shades with the shared headers and composites front to back.
// Slow (seconds for tens of thousands of pixels); small images only.
#include "bake/volume_upload.hpp"
#include "io/image.hpp"
#include "scene/scene.hpp"
#include "volume/volume.hpp"

#include <glm/glm.hpp>
#include <vector>

namespace cutaway::test {

/// The gradient bake on the CPU: the shared header's gradient weights and
/// encoding over the normalized texels, one (direction, magnitude) per voxel,
/// not yet quantized to the GPU's SNORM8.
std::vector<glm::vec4> cpuGradients(const Volume& volume, bake::ValueWindow window);

Image renderCpuReference(const Scene& scene, const Volume& volume);

} // namespace cutaway::test

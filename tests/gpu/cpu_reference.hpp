#pragma once
// An independent CPU renderer for tests: for every pixel it intersects the
// pixel's ray with the same view-aligned planes the GPU slices with, samples
// a CPU copy of the volume and its gradients (trilinear, clamp to edge),
// classifies, shades with the shared headers and composites front to back.
// Slow (seconds for tens of thousands of pixels); small images only.
#include "io/image.hpp"
#include "scene/scene.hpp"
#include "volume/volume.hpp"

namespace cutaway::test {

Image renderCpuReference(const Scene& scene, const Volume& volume);

} // namespace cutaway::test

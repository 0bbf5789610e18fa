#pragma once
// Pre-integrated classification (Engel, Kraus, Ertl, "High-Quality
// Pre-Integrated Volume Rendering", 2001). Slicing samples the volume once per
// slab; a thin or steep transfer-function feature then shows as rings where
// slices cut a surface. Pre-integration instead looks up the whole slab: entry
// (f, b) is the premultiplied colour and opacity of a ray segment of length
// `segmentMm` along which the normalized value goes linearly from s_f (front)
// to s_b (back), integrated with self-attenuation.
#include <glm/glm.hpp>
#include <vector>

namespace cutaway::render {

constexpr int kPreintegrationSize = 256;

/// `table` is the transfer function tabulated over the window (straight colour,
/// alpha per `referenceMm` of material, as tabulateTransfer gives). Returns
/// n * n premultiplied RGBA entries, front value along x (fastest), back along y.
/// The rows are shared among `threads` threads (0: one per hardware thread);
/// the table is the same for any count. Its cost grows as n^3 (about 5.6 M
/// exponentials at 256): a scene that animates its transfer function pays it
/// at every frame, once per label layer.
std::vector<glm::vec4> preintegrate(const std::vector<glm::vec4>& table, double referenceMm,
                                    double segmentMm, int n = kPreintegrationSize,
                                    unsigned threads = 0);

} // namespace cutaway::render

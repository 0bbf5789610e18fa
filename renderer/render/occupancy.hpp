#pragma once
// Empty-space skipping for slicing (docs/performance.md). The volume is cut
// into bricks of kBrickVoxels^3; a brick is occupied when some transfer
// function gives opacity to a value between the smallest and largest value of
// the brick and its 26 neighbours (so trilinear samples and pre-integrated
// slabs up to a brick long that reach into it are covered). Occupied bricks
// are merged into boxes (runs along x, then equal runs along y), and the
// volume's background proxy becomes those boxes: the slices' polygons cover
// only where something can show, and empty air is never rasterized.
#include "bake/volume_upload.hpp"
#include "render/camera.hpp"
#include "scene/scene.hpp"
#include "volume/volume.hpp"

#include <vector>

namespace cutaway::render {

constexpr int kBrickVoxels = 8;

/// World-space boxes that together cover every occupied brick of `scan`
/// (whose box in the world is `box`), for values normalized over `window`
/// and classified by any of `transfers`. Boxes do not overlap.
std::vector<Box> occupiedBoxes(const Volume& scan, const Box& box, bake::ValueWindow window,
                               const std::vector<const TransferFunction*>& transfers);

} // namespace cutaway::render

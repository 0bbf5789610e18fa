#pragma once
// What label volumes turn into on the way to the device: each voxel's
// classification layer (classification by label) and the indicator of a
// segment of interest (segment alignment). Host-side, one pass over the voxels.
#include "scene/scene.hpp"
#include "volume/volume.hpp"

#include <cstdint>
#include <vector>

namespace cutaway::render {

/// Per voxel: 0 for /transfer, i + 1 for the first entry of `transfers` that
/// lists the voxel's label. At most 255 entries.
std::vector<std::uint8_t> classLayers(const Volume& labels,
                                      const std::vector<LabelTransfer>& transfers);

/// Per voxel: 1 where the label is one of `ids`, else 0.
std::vector<std::uint8_t> labelIndicator(const Volume& labels,
                                         const std::vector<std::int64_t>& ids);

/// Per voxel: 1 where the value (after slope/intercept) lies in [lo, hi], else 0.
std::vector<std::uint8_t> rangeIndicator(const Volume& scan, double lo, double hi);

} // namespace cutaway::render

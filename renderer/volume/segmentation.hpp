#pragma once
// Background segmentation for surface alignment (paper section 4.2): the
// background is the air around the object, the voxels at or below a threshold
// that are connected (6-neighbours) to the border of the volume. Cavities
// inside the object (CSF, ventricles, sinuses) belong to the object, so the
// distance to the surface is measured from the outside only.
#include "volume/volume.hpp"

#include <cstdint>
#include <vector>

namespace cutaway {

/// Per voxel (x fastest): 1 for the object, 0 for the background as above.
/// `threshold` is in the volume's physical values.
std::vector<std::uint8_t> objectMask(const Volume& volume, double threshold);

} // namespace cutaway

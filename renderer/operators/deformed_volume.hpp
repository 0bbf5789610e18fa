#pragma once
// The deformed and cut volume as a regular grid, for other tools (ParaView,
// 3D Slicer): every voxel of the output is a point p' of the deformed space,
// mapped back through the operator whose deformed box holds it (the analytic
// continuous T_B of the shared header, Eq. 2, 6, 8) and sampled trilinearly.
// CPU only: no device needed.
#include "scene/scene.hpp"
#include "volume/volume.hpp"

#include <vector>

namespace cutaway::operators {

/// A volume and where its box lies in the world (mm): [worldLo, worldLo + extent].
/// A scan as loaded is centred on the origin; a resampled one may have grown.
struct PlacedVolume {
    Volume volume;
    glm::dvec3 worldLo{0.0};
};

/// The scan as the scene places it: centred on the world's origin.
PlacedVolume centred(Volume volume);

/// Resamples `in` deformed by `operators` (which must not overlap) on a grid
/// with its spacing that covers it and every operator's material (so a lifted
/// flap is kept). Voxels in a cut, or with no pre-image in the volume, get
/// `emptyValue`. The result is float32; untouched voxels keep their values
/// and positions (its `origin` moves with the grid).
PlacedVolume resampleDeformed(const PlacedVolume& in, const std::vector<OperatorSpec>& operators,
                              float emptyValue);

/// Sequential composition (the paper's "save the intermediate volume"): each
/// operator applies to the volume the previous ones left.
PlacedVolume resampleSequentially(const PlacedVolume& in,
                                  const std::vector<OperatorSpec>& operators, float emptyValue);

} // namespace cutaway::operators

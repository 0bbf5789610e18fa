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

/// Resamples `volume` deformed by `operators` on a grid with the volume's
/// spacing that covers the volume and every operator's deformed box (so a
/// lifted flap is kept). Voxels in a cut, or with no pre-image in the volume,
/// get `emptyValue`. The result is float32; its origin is shifted so that
/// untouched voxels keep their physical positions.
Volume resampleDeformed(const Volume& volume, const std::vector<OperatorSpec>& operators,
                        float emptyValue);

} // namespace cutaway::operators

#pragma once
// Placements given in a scan's physical coordinates ("space": "lps" or "ras")
// turned into the volume frame the renderer works in: millimetres along the
// voxel grid's axes, the volume's centre at the origin. A scan's voxel i lies
// at origin + direction * (spacing * i) in LPS (volume.hpp), and at
// (i + 1/2) * spacing - extent / 2 in the volume frame; RAS is LPS with x and
// y negated. A box or model placed in LPS or RAS keeps its shape there; its
// axes are those of that space, carried into the volume frame by the same map.
#include "scene/scene.hpp"
#include "volume/volume.hpp"

#include <string>

namespace cutaway::job {

/// The affine map from `space` to the volume frame of `scan` (only its
/// geometry is read: dims, spacing, origin, direction, space). Throws
/// InputError naming `pointer` and `scanName` when `space` is LPS or RAS and
/// the scan has no anatomical coordinates (Space::LPS).
glm::dmat4 spaceToVolumeFrame(const Volume& scan, CoordinateSpace space, const std::string& pointer,
                              const std::string& scanName);

/// Whether any placement of `scene` is given in LPS or RAS.
bool placedInScanSpace(const Scene& scene);

/// `scene` with every placement given in LPS or RAS turned into the volume
/// frame of `scan` (the scan as loaded: loadSceneVolume), their space then
/// Volume. A scene placed in the volume frame alone is returned unchanged.
Scene inVolumeFrame(const Scene& scene, const Volume& scan);

/// The scan's geometry without its voxels, to keep beside a render's volume.
Volume geometryOf(const Volume& scan);

} // namespace cutaway::job

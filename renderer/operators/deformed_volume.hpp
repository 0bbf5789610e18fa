#pragma once
// The deformed and cut volume as a regular grid, for other tools (ParaView,
// 3D Slicer): every voxel of the output is a point p' of the deformed space,
// mapped back through the operator whose deformed box holds it (the analytic
// continuous T_B of the shared header, Eq. 2, 6, 8), kept in place where an
// aligned operator's feature is (Eq. 3, 4 with the masks of shared/feature.h)
// and sampled trilinearly. CPU only: no device needed.
#include "scene/scene.hpp"
#include "volume/volume.hpp"

#include <functional>
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

/// Makes the field an aligned operator's feature mask M comes from, on the
/// grid of the volume `op` applies to (x fastest), as the renderer bakes it
/// (bake/feature_bake.hpp): the distance field DT in mm for surface
/// alignment, the encoded smoothed segment for segment alignment.
using FeatureFieldMaker =
    std::function<std::vector<float>(const Volume& volume, const OperatorSpec& op)>;

/// Resamples `in` deformed by `operators` (which must not overlap) on a grid
/// with its spacing that covers it and every operator's material (so a lifted
/// flap is kept). Voxels in a cut, or with no pre-image in the volume, get
/// `emptyValue`. The result is float32; untouched voxels keep their values
/// and positions (its `origin` moves with the grid). `fieldFor` makes the
/// feature fields of the operators that are not axis-aligned; without it
/// every operator is evaluated as axis-aligned.
PlacedVolume resampleDeformed(const PlacedVolume& in, const std::vector<OperatorSpec>& operators,
                              float emptyValue, const FeatureFieldMaker& fieldFor = {});

/// Sequential composition (the paper's "save the intermediate volume"): each
/// operator applies to the volume the previous ones left (and an aligned
/// one's feature field is made from that volume).
PlacedVolume resampleSequentially(const PlacedVolume& in,
                                  const std::vector<OperatorSpec>& operators, float emptyValue,
                                  const FeatureFieldMaker& fieldFor = {});

} // namespace cutaway::operators

#pragma once
// `cutaway export`: the deformed and cut volume of one frame on a regular
// grid, on the CPU. Aligned operators keep their feature in place as the
// render does: the distance field or segment mask is made on the CPU by the
// bakes' twins (bake/feature_bake.hpp), from the volume each operator
// applies to.
#include "operators/deformed_volume.hpp"
#include "scene/scene.hpp"
#include "volume/volume.hpp"

#include <vector>

namespace cutaway::job {

/// The feature field `op`'s alignment reads, made from `volume` (the scan,
/// or under sequential composition the volume the operators before it left)
/// as the renderer bakes it: the distance field DT in mm of the object above
/// the alignment's threshold (Otsu's without one), or the segment mask of its
/// labels (`labels`, on `volume`'s grid) or value range. Throws InputError
/// naming the operator when its segment is empty or needs absent labels.
std::vector<float> featureFieldCpu(const Volume& volume, const Volume* labels,
                                   const OperatorSpec& op);

/// The volume of `scene` (one frame: see sceneAtFrame) deformed by all its
/// operators, in their composition. Cuts and openings take the scan's
/// smallest value (air in CT, background in MRI).
Volume exportVolume(const Scene& scene);

} // namespace cutaway::job

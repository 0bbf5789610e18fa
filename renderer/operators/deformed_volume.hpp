#pragma once
// The deformed and cut volume as a regular grid, for other tools (ParaView,
// 3D Slicer): every voxel of the output is a point p' of the deformed space,
// mapped back through the operator whose deformed box holds it (the analytic
// continuous T_B of the shared header, Eq. 2, 6, 8), kept in place where an
// aligned operator's feature is (Eq. 3, 4 with the masks of shared/feature.h)
// and sampled trilinearly; material that moves off a segment reads the
// values the renderer's region texture holds (moved_value.hpp). CPU only: no
// device needed.
#include "scene/scene.hpp"
#include "volume/volume.hpp"

#include <functional>
#include <memory>
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

/// The field an aligned operator's feature mask M comes from, on the grid of
/// the volume the operator applies to (x fastest), as the renderer bakes it
/// (bake/feature_bake.hpp): the distance field DT in mm for surface
/// alignment, the encoded smoothed segment for segment alignment.
using FeatureField = std::shared_ptr<const std::vector<float>>;
/// Makes (or finds) the feature field of `op`'s alignment for `volume`; `op`
/// is an element of the operator list given to resampleDeformed or
/// resampleSequentially (its address is stable while they run).
using FeatureFieldMaker = std::function<FeatureField(const Volume& volume, const OperatorSpec& op)>;

/// How resampleDeformed reads the input at a point.
enum class Sampling {
    Trilinear, ///< physical values, interpolated; the result is float32 (a scan)
    Nearest    ///< the nearest voxel's stored number, in the input's type (labels)
};

/// How resampleDeformed reads the input, and at what grid.
struct Resampling {
    Sampling sampling = Sampling::Trilinear;
    /// No voxel of a segment-aligned operator's segment leaves with the
    /// operator (shared/feature.h segmentMask), as where labels classify the
    /// frame; otherwise material leaves unless the smoothed segment holds it
    /// (it crosses 0.5 between voxels), as the renderer's value-classified
    /// frames do. A point of the segment's voxels stays either way. Nearest
    /// sampling (labels) always keeps them.
    bool keepSegmentVoxels = false;
    /// K > 1: a grid K times finer along each axis (see resampleDeformed).
    int oversample = 1;
};

/// Resamples `in` deformed by `operators` (which must not overlap) on a grid
/// with its spacing that covers it and every operator's material (so a lifted
/// flap is kept). Voxels in a cut, or with no pre-image in the volume, get
/// `emptyValue` (Nearest: the stored number 0, a label volume's background).
/// Untouched voxels keep their values and physical positions (the result's
/// `origin` moves with the grid along `in`'s directions, which it keeps). `fieldFor` makes the
/// feature fields of the operators that are not axis-aligned, on `in`'s grid; without it every
/// operator is evaluated as axis-aligned.
/// With `how.oversample` K > 1 the grid's spacing is `in`'s divided by K over the
/// same box (each input voxel's box holds K^3 output voxels), so cut faces
/// are resolved K times finer; untouched voxels are then trilinear samples.
PlacedVolume resampleDeformed(const PlacedVolume& in, const std::vector<OperatorSpec>& operators,
                              float emptyValue, const FeatureFieldMaker& fieldFor = {},
                              const Resampling& how = {});

/// Sequential composition (the paper's "save the intermediate volume"): each
/// operator applies to the volume the previous ones left (and an aligned
/// one's feature field is made from that volume).
/// With `how.oversample`, only the last operator's step takes the finer grid.
PlacedVolume resampleSequentially(const PlacedVolume& in,
                                  const std::vector<OperatorSpec>& operators, float emptyValue,
                                  const FeatureFieldMaker& fieldFor = {},
                                  const Resampling& how = {});

} // namespace cutaway::operators

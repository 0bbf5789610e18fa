#pragma once
// `cutaway export`: the deformed and cut volume of one frame on a regular
// grid, on the CPU. Aligned operators keep their feature in place as the
// render does: the distance field or segment mask is made on the CPU by the
// bakes' twins (bake/feature_bake.hpp), from the volume each operator
// applies to.
#include "operators/deformed_volume.hpp"
#include "scene/scene.hpp"
#include "volume/volume.hpp"

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
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

/// What `cutaway export` writes for one frame. Both volumes have the scan's
/// spacing, directions and space, and an origin that puts every voxel of the
/// scan's grid where the scan has it (physicalPosition): the grid grows by
/// whole voxels along the scan's index axes to hold what operators move out.
struct Exported {
    Volume volume; ///< the scan deformed, float32
    /// The scan's voxel type and scaling as read: writeExport stores the
    /// volume in them where its values fit (ExportRequest::type).
    VoxelType sourceType = VoxelType::F32;
    double sourceSlope = 1.0, sourceInter = 0.0;
    std::optional<Volume> labels;      ///< the label volume deformed alike, when asked for
    std::vector<std::string> warnings; ///< what a render would warn of (operators outside)
};

/// The volume of `scene` (one frame: see sceneAtFrame) deformed by all its
/// operators, in their composition. Cuts and openings take the scan's
/// smallest value (air in CT, background in MRI). With `withLabels`, also
/// its label volume (/labels, which the scene must have) through the same
/// maps, each voxel taking the label nearest to its pre-image: ids are never
/// blended, and cuts are background (0).
/// With `oversample` K > 1 both grids are K times finer along each axis
/// over the same box (resampleDeformed), so cut faces alias K times less.
Exported exportVolume(const Scene& scene, bool withLabels = false, int oversample = 1);

/// Where an export goes: the volume's file (NRRD or NIfTI-1, by its name),
/// and its labels' when asked for.
struct ExportRequest {
    std::filesystem::path output;
    std::optional<std::filesystem::path> labelsOutput;
    bool compress = true; ///< gzip; false writes raw
    int oversample = 1;   ///< --oversample, [1, kMostOversample]
    /// --type: the voxel type written; none ("auto"): the scan's own where
    /// every resampled value, rounded for an integer type, fits it (with the
    /// scan's slope and intercept), else float32; float32 for a scaled scan
    /// written as NRRD, which has no standard scaling.
    std::optional<VoxelType> type;
};

/// `exported`'s volume stored as `type` with the scan's scaling, each value
/// rounded for an integer type; none when a value does not fit the type.
std::optional<Volume> storedAs(const Exported& exported, VoxelType type);

/// The finest --oversample: 4^3 = 64 voxels for each of the scan's.
inline constexpr int kMostOversample = 4;

/// Refuses an output not named .nrrd, .nii or .nii.gz, or a .nii.gz with
/// compression off (InputError naming -o).
void checkExportName(const ExportRequest& request);

/// Refuses what `cutaway export` cannot write for `scene` (one frame): a
/// labels output not named as -o may be named, or asked of a scene without /labels
/// (naming --labels-output and `sceneName`), and outputs that are files the
/// frame reads or each other (checkExportPaths). InputError.
void checkExportRequest(const Scene& scene, const std::string& sceneName,
                        const ExportRequest& request);

/// Writes `exported` as `request` says, making missing folders: both files
/// or neither (a failed labels file removes the volume's). Calls `wrote`
/// after each file.
void writeExport(const Exported& exported, const ExportRequest& request,
                 const std::function<void(const std::filesystem::path&, const Volume&)>& wrote);

} // namespace cutaway::job

#pragma once
// A scene's data, loaded in one step before anything goes to a device: the
// scan (a file or a phantom) with its non-finite voxels made empty, its
// labels checked against its grid, its value window, and under sequential
// composition the scan deformed by every operator but the last. The frame
// takes it whole (FrameVolume).
#include "bake/volume_upload.hpp"
#include "scene/scene.hpp"
#include "volume/volume.hpp"

#include <array>
#include <cstddef>
#include <filesystem>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

namespace cutaway::job {

/// The scene's volume: read from its file (or made as its phantom), with the
/// spacing override applied. Its NaN and infinite voxels (a float file's)
/// are left out of its value range and the automatic window, and take the
/// value of empty space (emptyValue), so they render as empty; `nonFinite`,
/// if given, receives how many there were. Throws InputError naming the file
/// on failure.
Volume loadSceneVolume(const Scene& scene, std::size_t* nonFinite = nullptr);

/// The warning for a volume with `count` non-finite voxels of `voxels`.
std::string nonFiniteWarning(const Scene& scene, std::size_t count, std::size_t voxels);

/// The scene's label volume (/labels), or null without one: read from its
/// file or made with the phantom, checked against the scan's grid (same dims,
/// spacing equal to within 0.1 %; /volume/spacing applies to both), with
/// integer ids >= 0. Throws InputError naming the file on a mismatch. When
/// /labels names the scan's own file (a label volume rendered as itself), the
/// scan is checked and returned: the file is read and held once.
std::shared_ptr<const Volume> loadSceneLabels(const Scene& scene,
                                              const std::shared_ptr<const Volume>& scan);

/// The value window: the scene's, else the volume's value range (a flat
/// volume gets a window of width 1 so normalization stays defined). Where
/// the scene's window cuts the range off, the voxels beyond classify as the
/// volume's extreme values (ValueWindow::below, above).
bake::ValueWindow sceneWindow(const Scene& scene, const Volume& volume);
/// The same from the volume's value range (valueRange), already at hand.
bake::ValueWindow sceneWindow(const Scene& scene, ValueRange range);

/// What empty space (cuts, openings, the space a flap lifts into) holds when
/// the CPU resamples the scan (sequential composition, `cutaway export`): the
/// lower of the scan's smallest value and the window's bottom. Transparent
/// under any transfer function that is transparent for air, and background
/// to an aligned operator's threshold or value range made from the result.
float emptyValue(const Scene& scene, const Volume& scan);

/// Whether the frame resamples the scan on the CPU: sequential composition
/// with more than one operator (all but the last are baked into the volume).
bool sequential(const Scene& scene);

/// A warning for each label a scene lists (in /transfer/labels or a segment
/// alignment's labels) that no voxel of `labels` carries: a typo in an id, or
/// an atlas table's label this scan lacks.
std::vector<std::string> absentLabelWarnings(const Scene& scene, const Volume& labels);

/// The volume a frame renders and its value window: the scan itself, or under
/// sequential composition the scan deformed by every operator but the last
/// (resampled on the CPU). The window is always the scan's.
struct FrameVolume {
    std::shared_ptr<const Volume> scan;
    glm::dvec3 worldLo{0.0}; ///< where the scan's corner lies in the world
    bake::ValueWindow window;
    std::shared_ptr<const Volume> labels; ///< on the scan's grid (maybe the scan), or null
    std::size_t nonFinite = 0; ///< NaN and infinite voxels the scan's file held (now empty)
    /// The scan's geometry as loaded (no voxels), which places what a scene
    /// gives in LPS or RAS (job/volume_frame.hpp).
    Volume geometry;
};
FrameVolume frameVolume(const Scene& scene);

/// What the volume frameVolume makes comes from, so a sequence uploads it
/// again only when it changes: the /volume section, the /labels source, and
/// under sequential composition every operator but the last.
struct FrameVolumeKey {
    VolumeSource volume;
    bool labels = false;
    std::filesystem::path labelsFile;
    bool labelsPhantom = false;
    std::vector<std::array<float, 12>> bakedParams; ///< sequential: the baked operators'
    std::vector<glm::dmat4> bakedPlacements;
    std::vector<CoordinateSpace> bakedSpaces; ///< the frames bakedPlacements are in
    bool operator==(const FrameVolumeKey&) const = default;
};
FrameVolumeKey frameVolumeKey(const Scene& scene);

/// The operators rendered live through their baked maps: all of them, or
/// under sequential composition only the last.
std::vector<OperatorSpec> liveOperators(const Scene& scene);

} // namespace cutaway::job

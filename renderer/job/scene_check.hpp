#pragma once
// What `cutaway validate` checks beyond a scene's JSON, without a device: the
// files its frames name, read and checked as a render would, and the warnings
// a render would give.
#include "job/scene_data.hpp"
#include "job/value_checks.hpp"
#include "scene/scene.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace cutaway::job {

/// An operator whose own box V_T misses the volume's box [lo, hi] (world mm):
/// it cuts, moves and keeps nothing. One per such operator, by its index in
/// /operators, with the warning a render prints.
struct OperatorOutside {
    std::size_t index = 0;
    std::string message;
};
std::vector<OperatorOutside> operatorsOutside(const Scene& scene, glm::dvec3 lo, glm::dvec3 hi);

/// Checks the frames of a run one by one as rendering them would, without a
/// device: reads the volume (or makes the phantom) and the label volume
/// (checked against the scan's grid) once per distinct pair, and each glTF
/// model once; refuses overlapping operators and a segment-aligned operator
/// whose segment holds no voxel. Collects the warnings a render would print
/// (operators outside the volume), each operator once. Under sequential
/// composition the intermediate volume is not resampled: operators are
/// checked against the scan's box, and overlaps and segments not at all.
class SceneFileCheck {
public:
    /// Throws InputError naming the file or the JSON pointer of the first
    /// thing this frame's render would refuse.
    void frame(const Scene& scene);
    std::vector<std::string> takeWarnings() { return std::exchange(m_warnings, {}); }
    /// What the frames derive from their scans (job/value_checks.hpp), each once.
    std::vector<std::string> takeNotes() { return std::exchange(m_notes, {}); }

private:
    struct Files {
        FrameVolumeKey key;
        std::shared_ptr<const Volume> scan, labels;
        std::string error;         ///< why reading them failed, or ""
        std::size_t nonFinite = 0; ///< the scan's NaN and infinite voxels (warned of once)
    };
    /// The index in m_files of the files `scene` reads, read on first use.
    std::size_t filesOf(const Scene& scene);
    /// A segment-aligned operator's check: its files, its segment, and the
    /// operator (the message names it).
    struct SegmentKey {
        std::size_t files = 0;
        std::vector<std::int64_t> labels;
        std::optional<std::array<double, 2>> range;
        std::size_t operatorIndex = 0;
        std::string name;
        auto operator<=>(const SegmentKey&) const = default;
    };

    std::vector<Files> m_files;                   ///< each distinct pair of files read
    std::map<SegmentKey, std::string> m_segments; ///< segment checked -> its error, or ""
    std::set<std::string> m_meshesRead;
    std::set<std::size_t> m_warned;
    std::set<std::size_t> m_warnedFiles; ///< m_files whose non-finite voxels were warned of
    std::set<std::string> m_warnedOnce;  ///< absent-label and value warnings already given
    std::vector<std::string> m_warnings;
    ValueChecks m_values;
    std::set<std::string> m_noted;
    std::vector<std::string> m_notes;
};

} // namespace cutaway::job

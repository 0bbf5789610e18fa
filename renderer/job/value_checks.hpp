#pragma once
// What a scene's values are likely to do wrong, checked against the scan as
// read, for `render` and `validate` to warn of, and what they derive from the
// scan that a user needs to set values (for `validate` to note):
//  * a transfer function whose visible part (alpha > 0) misses the scan's
//    values, or whose points all lie in [0, 1] on a scan whose values span a
//    hundred or more (a function copied from a normalized example);
//  * voxels outside /volume/window whose visibility the window changes (the
//    texture holds the window; a value beyond it is drawn as the volume's
//    extreme on that side, bake::ValueWindow, which a visible band between
//    them sets apart).
#include "scene/scene.hpp"
#include "volume/volume.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace cutaway::job {

/// Where a transfer function is visible: the values with alpha > 0 lie in
/// [lo, hi] (infinite where the end point's alpha, which holds beyond it, is
/// above 0); `any` false when alpha is 0 everywhere.
struct VisiblePart {
    bool any = false;
    double lo = 0.0;
    double hi = 0.0;
};
VisiblePart visiblePart(const TransferFunction& tf);

/// The warnings above for `scene` on `scan` (the scan as loaded, before any
/// resampling), each naming its JSON pointer.
std::vector<std::string> valueWarnings(const Scene& scene, const Volume& scan);

/// What validate notes: the scan's value range, the window, and the
/// threshold each surface-aligned operator without one takes (Otsu's).
std::vector<std::string> valueNotes(const Scene& scene, const Volume& scan);

/// valueWarnings and valueNotes for the frames of a run, each made again
/// only when what it depends on changes: the scan (`scanId`: the same id,
/// the same voxels), the transfer functions, the window, the operators whose
/// threshold is Otsu's. A frame is checked, not only the first.
class ValueChecks {
public:
    const std::vector<std::string>& warnings(const Scene& scene, const Volume& scan,
                                             std::uint64_t scanId);
    const std::vector<std::string>& notes(const Scene& scene, const Volume& scan,
                                          std::uint64_t scanId);

private:
    struct Key {
        std::uint64_t scan = 0;
        std::vector<TransferFunction> transfers;
        std::optional<std::array<double, 2>> window;
        std::vector<int> otsuOperators;
        bool operator==(const Key&) const = default;
    };
    static Key keyOf(const Scene& scene, std::uint64_t scanId, bool forNotes);
    /// `lines`, made again by `make` when `key` is not the one they were made for.
    template <typename Make>
    static const std::vector<std::string>& cached(std::optional<Key>& madeFor,
                                                  std::vector<std::string>& lines, Key key,
                                                  const Make& make) {
        if (madeFor != key) {
            lines = make();
            madeFor = std::move(key);
        }
        return lines;
    }
    std::optional<Key> m_warningsKey, m_notesKey;
    std::vector<std::string> m_warnings, m_notes;
};

} // namespace cutaway::job

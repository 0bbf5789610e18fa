#pragma once
// Empty-space skipping for slicing (docs/design/empty-space.md). The volume is cut
// into bricks of kBrickVoxels^3; a brick is occupied when some transfer
// function gives opacity to a value between the smallest and largest voxel
// that a sample in the brick, or a slab that starts there, can read: the
// brick's voxels, one more on every side (trilinear filtering) and a margin
// of m more, which covers slabs up to m + 0.5 voxels long along each axis (a
// sample lies up to half a voxel inside the outermost voxel centres).
// Occupied bricks are merged into boxes (runs along x, then equal runs along
// y), and the volume's background proxy becomes those boxes: the slices'
// polygons cover only where something can show, and empty air is never
// rasterized. The ray caster's finer cells (ray_cells.hpp) work the same way.
#include "bake/volume_upload.hpp"
#include "render/camera.hpp"
#include "scene/scene.hpp"
#include "shared/tuning.h"
#include "shared/visible_runs.h"
#include "volume/volume.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace cutaway::render {

using shader::kBrickVoxels; // shared/tuning.h

/// Which normalized values (over the window) the frame's classification can
/// give opacity to, in the bins of the table the shaders read: the 1D
/// function's entries (post-classification) or the pre-integrated table's,
/// whose entries resample the function (so a visible entry of the function
/// makes its neighbours in the coarser table visible too).
class VisibleValues {
public:
    VisibleValues(const std::vector<const TransferFunction*>& transfers, bake::ValueWindow window,
                  bool preintegrated);
    /// Whether a sample, or a slab whose two ends are, between lo and hi can
    /// have opacity: some bin from floor(lo * (n - 1)) to ceil(hi * (n - 1))
    /// (the table's linear filtering) is visible for some function.
    bool anyIn(float lo, float hi) const;
    /// Per bin i, the first visible bin from i on (the bin count when none;
    /// one entry more, for i = the bin count), so anyIn is
    /// firstFrom[first] < end (runs() gives the ray caster the same).
    const std::vector<int>& firstFrom() const { return m_firstFrom; }
    /// The visible bins as at most CW_VISIBLE_RUNS runs [lo[i], hi[i]), the
    /// others empty (0, 0), for the ray caster's runsMayShow
    /// (shaders/shared/visible_runs.h), which then answers as anyIn. More
    /// runs than that are joined across the narrowest gaps between them: the
    /// test then also passes slabs whose bins show nothing (they classify to
    /// no opacity, so the image is the same), and still every one that shows.
    using Runs = shader::VisibleRuns;
    Runs runs() const;

private:
    std::vector<int> m_firstFrom;
};

/// The smallest and largest of some normalized values (lo > hi: none), in
/// steps of 1 / kSpanSteps rounded outward: 2 bytes a cell instead of 8 (the
/// ray caster's cells of 2^3 voxels number an eighth of the voxels, and their
/// spans stay for the next transfer function). The steps are the bins of the
/// pre-integrated tables (kPreintegrationSize), so for them a span is at most
/// a rounding wider where anyIn looks; for a post-classified table's 1024 bins,
/// up to 4 bins wider. Wider spans only flag more cells: never a wrong skip.
constexpr int kSpanSteps = 255;
struct ValueSpan {
    uint8_t lo = kSpanSteps, hi = 0;
    /// The span of the values in [lo, hi] (normalized, in [0, 1]); its ends
    /// as floats (low(), high()) hold them, whatever the products round to.
    static ValueSpan covering(float lo, float hi) {
        int a = static_cast<int>(std::floor(lo * float(kSpanSteps)));
        int b = static_cast<int>(std::ceil(hi * float(kSpanSteps)));
        if (a > 0 && float(a) / float(kSpanSteps) > lo) --a;
        if (b < kSpanSteps && float(b) / float(kSpanSteps) < hi) ++b;
        return {static_cast<uint8_t>(a), static_cast<uint8_t>(b)};
    }
    void add(const ValueSpan& s) {
        lo = std::min(lo, s.lo);
        hi = std::max(hi, s.hi);
    }
    bool empty() const { return lo > hi; }
    float low() const { return float(lo) / float(kSpanSteps); }
    float high() const { return float(hi) / float(kSpanSteps); }
};

/// Per cell of `cellVoxels`^3 (x fastest; the last ones partial), the span of
/// the values normalized over `window` (clamped to [0, 1]) of the voxels
/// within `extra` of the cell, clamped to the volume. The spans depend on the
/// scan, the window and the reach, not on the transfer functions: a new
/// classification only re-flags the cells.
struct SpanGrid {
    glm::ivec3 cells{0};
    int cellVoxels = 0;
    std::vector<ValueSpan> spans;
};
SpanGrid spanGrid(const Volume& scan, bake::ValueWindow window, int cellVoxels, int extra);

/// The grid of cells twice as large, each the union of its 2x2x2 cells'
/// spans: what spanGrid gives at twice the size with the same extra (the
/// reaches of two neighbouring cells are contiguous, clamped alike).
SpanGrid coarsened(const SpanGrid& fine);

/// The smallest margin m (voxels) that covers slabs `slabVoxels` long along
/// each axis: m + 0.5 >= slabVoxels.
int slabMargin(double slabVoxels);

/// Cells [lo, hi) of a grid.
struct CellRun {
    glm::ivec3 lo, hi;
};

/// Boxes of cells that together cover the cells flagged non-zero in `flags`
/// (x fastest) without overlapping: runs along x, then equal runs of
/// consecutive rows merged along y.
std::vector<CellRun> mergeCells(glm::ivec3 dims, const std::vector<uint8_t>& flags);

/// Which bricks of a scan are occupied, and where they lie in the world.
struct BrickOccupancy {
    glm::ivec3 bricks{0};
    Box box;                    ///< the volume's box in the world
    glm::dvec3 brickMm{0.0};    ///< a brick's extent in mm
    std::vector<uint8_t> flags; ///< per brick, x fastest: 1 occupied
    /// Summed-area table over the bricks, (bricks + 1)^3 entries: anyIn in O(1).
    std::vector<uint32_t> sums;

    /// Whether some occupied brick meets the world-space box [lo, hi].
    bool anyIn(glm::dvec3 lo, glm::dvec3 hi) const;
    /// World-space boxes that together cover every occupied brick (runs along
    /// x, then equal runs of rows merged along y). Boxes do not overlap.
    std::vector<Box> boxes() const;
};

/// The occupancy of the bricks whose spans (kBrickVoxels cells, reaching 1 +
/// the slab margin) are `bricks`, in a volume whose box in the world is `box`
/// with voxels `spacing` mm apart, where `visible` says which values can show.
BrickOccupancy brickOccupancy(const SpanGrid& bricks, const Box& box, glm::dvec3 spacing,
                              const VisibleValues& visible);

/// The same from the scan, for values normalized over `window`, with a margin
/// of `marginVoxels` for slabs.
BrickOccupancy brickOccupancy(const Volume& scan, const Box& box, bake::ValueWindow window,
                              const VisibleValues& visible, int marginVoxels);

/// Every brick occupied: for a volume whose values are not on the host.
BrickOccupancy fullOccupancy(const Box& box);

} // namespace cutaway::render

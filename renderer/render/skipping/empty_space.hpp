#pragma once
// Everything that skips a frame's empty space, in one owner: the spans of
// values over the volume's cells and bricks (one pass over the scan per
// volume, window and slab margin), the occupancy the scene's classification
// gives them (remade when a transfer function's opacity changes), and per
// operator the regions where its shader can show something (slicing's boxes,
// the ray caster's block distances) and the cases of Eq. 4 they come from.
// Each part is made on first use and kept while its key (a struct compared
// whole: a field left out of a key cannot go unnoticed) stays the same.
#include "bake/volume_upload.hpp"
#include "gpu/context.hpp"
#include "gpu/resources.hpp"
#include "operators/operator_geometry.hpp"
#include "render/feature_fields.hpp"
#include "render/gpu_operators.hpp"
#include "render/gpu_volume.hpp"
#include "render/skipping/case_occupancy.hpp"
#include "render/skipping/occupancy.hpp"
#include "scene/scene.hpp"

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <utility>
#include <vector>

namespace cutaway::render {

class EmptySpace {
public:
    /// `features`: the operators' feature fields, whose ranges refine where
    /// each case of Eq. 4 can show (kept by reference).
    EmptySpace(const gpu::Context& ctx, FeatureFields& features);

    /// Whether operator shaders run only where something can show (on by
    /// default): slicing shades only the regions, rays step over the empty
    /// blocks. Off, they run over the whole deformed box, as the tests that
    /// compare the two need.
    void setOperatorSkipping(bool on) { m_operatorSkipping = on; }
    bool operatorSkipping() const { return m_operatorSkipping; }

    /// Brings the spans and the occupancy up to date with `scene`'s
    /// classification of `volume`, for slabs up to `marginVoxels` long
    /// (slabMargin), and forgets the regions of operators past `operators`.
    void update(const Scene& scene, const GpuVolume& volume, int marginVoxels,
                std::size_t operators);

    const BrickOccupancy& occupancy() const { return m_occupancy; }
    /// The occupied bricks merged into boxes: the volume's slicing proxies.
    const std::vector<Box>& occupiedBoxes() const { return m_occupied; }
    /// The ray caster's cells' spans (null without the scan on the host).
    const SpanGrid* cellSpans() const { return m_cellSpans ? &*m_cellSpans : nullptr; }
    /// What the frame's classification can show.
    const VisibleValues& visible() const { return *m_visible; }
    /// Counts the occupancy's remakes: what caches derived from it key on.
    std::uint64_t occupancySerial() const { return m_occupancySerial; }

    /// Slicing's regions of operator `index`: its active blocks merged into
    /// boxes of its local frame, of the blocks where a brick is occupied (not
    /// the feature field: finer regions split the box into more polygons,
    /// whose T-junctions leave seams of pixels shaded twice or not at all).
    /// `reachMm`: the frame's longest slab.
    const std::vector<operators::LocalBox>& regionBoxes(std::size_t index, const GpuOperator& op,
                                                        double reachMm);
    /// The ray caster's blocks of operator `index`: the chessboard distances
    /// (R8_UINT storage image) of the blocks where each case of Eq. 4 can
    /// show something, exact for rays; one active block when operator
    /// skipping is off.
    VkImageView blockDistances(std::size_t index, const GpuOperator& op, double reachMm);

private:
    /// What every part of an operator's regions depends on.
    struct RegionKey {
        std::uint64_t occupancySerial = 0;
        double reachMm = 0.0;
        std::uint64_t fieldId = 0;
        int alignment = 0;
        double depth = 0.0;
        std::array<float, sizeof(shader::OperatorParams) / sizeof(float)> params{};
        glm::dmat4 localToWorld{1.0};
        operators::LocalBox local;
        glm::ivec3 resolution{0};
        bool operator==(const RegionKey&) const = default;
    };
    struct Regions {
        RegionKey key;
        std::optional<std::vector<operators::LocalBox>> boxes; ///< slicing's
        gpu::Image distance;                                   ///< the ray caster's
    };
    /// What casesFor's answer depends on.
    struct CaseKey {
        std::uint64_t occupancySerial = 0;
        std::uint64_t fieldId = 0;
        double threshold = 0.0;
        int alignment = 0;
        auto operator<=>(const CaseKey&) const = default;
    };
    /// Operator `index`'s Regions, emptied when their key changes.
    Regions& regionsFor(std::size_t index, const GpuOperator& op, double reachMm);
    /// Where each case of Eq. 4 can show something for `op`, with its feature
    /// field's ranges where it has one (case_occupancy.hpp).
    const CaseOccupancy& casesFor(const GpuOperator& op);
    void updateSpans(const GpuVolume& volume, int marginVoxels);
    gpu::Image distanceImage(glm::ivec3 dims, const std::vector<uint8_t>& active) const;

    /// What the spans depend on.
    struct SpanKey {
        std::uint64_t volume = 0;
        bake::ValueWindow window;
        int marginVoxels = -1;
        bool operator==(const SpanKey&) const = default;
    };
    /// What the occupancy depends on: the spans', and the opacity of every
    /// point of the classifying transfer functions.
    struct OccupancyKey {
        SpanKey spans;
        bool preintegrated = false;
        std::vector<std::vector<std::pair<double, float>>> opacities;
        bool operator==(const OccupancyKey&) const = default;
    };

    const gpu::Context& m_ctx;
    FeatureFields& m_features;
    bool m_operatorSkipping = true;
    std::optional<SpanGrid> m_cellSpans;  ///< the ray caster's cells (null: no host scan)
    std::optional<SpanGrid> m_brickSpans; ///< the slicing bricks': the cells' unions
    std::optional<SpanKey> m_spanKey;
    std::optional<VisibleValues> m_visible;
    BrickOccupancy m_occupancy;
    std::vector<Box> m_occupied;
    std::optional<OccupancyKey> m_occupancyKey;
    std::uint64_t m_occupancySerial = 0;
    std::vector<Regions> m_regions; ///< per operator
    /// By occupancy serial, field, threshold and alignment: an operator that
    /// moves keeps its feature's cells (up to 4 MB on the frog).
    std::map<CaseKey, CaseOccupancy> m_cases;
    gpu::Image m_noSkipping; ///< the blocks when skipping is off: one, active
};

} // namespace cutaway::render

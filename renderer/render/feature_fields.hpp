#pragma once
// The feature textures of aligned operators (paper sections 4.2, 4.3): the
// distance field of surface alignment, the smoothed mask of segment
// alignment. Each is baked the first time an operator needs it and kept while
// the volume and the inputs it came from (threshold; labels or range, band)
// stay the same, so moving or animating an operator does not bake again.
#include "bake/feature_bake.hpp"
#include "bake/feature_ranges.hpp"
#include "render/gpu_volume.hpp"
#include "scene/scene.hpp"

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cutaway::render {

class FeatureFields {
public:
    /// `storageImages`: the fields are also read as storage images
    /// (OperatorStack); by default as the device's tuning says.
    FeatureFields(const gpu::Context& ctx, bool storageImages);
    explicit FeatureFields(const gpu::Context& ctx)
        : FeatureFields(ctx, ctx.tuning().storageImages()) {}

    /// The field `spec`'s alignment reads: R16F over the volume's grid
    /// (surface: DT in mm; segment: M, which the operator's shader reads
    /// through its region, bake/feature_region.hpp), or a 1^3 texture for
    /// axis alignment. Valid until the next call of keepOnly.
    /// `id`, if given, receives a number that differs between any two fields
    /// this object made (0: the 1^3 texture).
    const gpu::Image& fieldFor(const OperatorSpec& spec, const GpuVolume& volume,
                               std::uint64_t* id = nullptr);

    /// The ranges of the field whose id fieldFor gave, over cells of
    /// `cellVoxels`^3 voxels (bake/feature_ranges.hpp): made on first use and
    /// kept with the field. Null for id 0 (axis alignment) or an id no longer
    /// kept. Surface alignment's in steps of half a millimetre, segment
    /// alignment's in steps of 0.01 of M.
    const bake::FieldRanges* rangesOf(std::uint64_t id, int cellVoxels);

    /// Frees the fields none of `specs` reads. Called once per frame before
    /// fieldFor, so a field no longer wanted is gone before a new one bakes
    /// (switching alignment does not hold both at once).
    void keepOnly(const std::vector<OperatorSpec>& specs, const GpuVolume& volume);

    /// The background threshold surface alignment used, in the volume's
    /// values: the scene's, or Otsu's (computed once per volume).
    double threshold(const Alignment& alignment, const GpuVolume& volume);

    /// One line per field baked since the last call, e.g. "surface alignment:
    /// distance field at threshold 0.2 (Otsu), 0.31 s".
    std::vector<std::string> takeNotes();
    /// What each field fieldFor gave since the last keepOnly (this frame's)
    /// is, one line per field, without times ("peeler: distance field of the
    /// object above 0.2 (Otsu's threshold)"): the same for every frame that
    /// reads the same fields, whether it baked them or not.
    const std::vector<std::string>& fieldsInUse() const { return m_inUse; }
    int bakes() const { return m_bakes; }

private:
    /// What a field comes from, on one volume: equal keys, equal fields.
    struct FieldKey {
        AlignmentMode mode = AlignmentMode::Surface;
        double threshold = 0.0;                     ///< surface: the object's, resolved (Otsu's)
        double band = 0.0;                          ///< segment: the mask's smoothing
        std::optional<std::array<double, 2>> range; ///< segment: by values
        std::vector<std::int64_t> labels;           ///< segment: by labels
        auto operator<=>(const FieldKey&) const = default;
    };
    struct Described {
        FieldKey key;
        std::string note; ///< what the field is, for takeNotes
    };
    Described describe(const Alignment& alignment, const GpuVolume& volume);
    /// The segment of a segment alignment as an R8_UNORM texture, 1 inside;
    /// throws InputError naming the operator when it is empty.
    gpu::Image indicatorTexture(const OperatorSpec& spec, const GpuVolume& volume) const;

    const gpu::Context& m_ctx;
    bake::FeatureBaker m_baker;
    bake::FieldRangeBaker m_rangeBaker;
    gpu::Image m_none;
    std::uint64_t m_serial = 0;
    std::optional<double> m_otsu;
    struct Field {
        gpu::Image image;
        std::uint64_t id = 0;
        float rangeScale = 1.0f; ///< the ranges' steps per unit of the field
        std::optional<bake::FieldRanges> ranges;
    };
    std::map<FieldKey, Field> m_fields;
    std::uint64_t m_nextId = 1;
    std::vector<std::string> m_notes;
    std::vector<std::string> m_inUse;
    int m_bakes = 0;
};

} // namespace cutaway::render

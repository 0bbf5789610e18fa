#pragma once
// What label volumes turn into on the way to the device: each voxel's
// classification layer (classification by label) and the indicator of a
// segment of interest (segment alignment). Host-side, written straight into
// an upload's staging buffer a few slices at a time.
#include "scene/scene.hpp"
#include "volume/volume.hpp"

#include <cstdint>
#include <memory>
#include <optional>
#include <unordered_map>
#include <vector>

namespace cutaway::render {

class LabelLookup;

/// A byte per voxel from its label id, written a range of voxels at a time (an
/// upload stages a few slices, not the whole volume). Keeps a reference to
/// `labels`.
class LabelBytes {
public:
    LabelBytes(const Volume& labels, std::unordered_map<std::int64_t, std::uint8_t> map);
    ~LabelBytes();
    LabelBytes(LabelBytes&&) noexcept;
    /// The bytes of voxels [first, first + count), x fastest.
    void write(std::size_t first, std::size_t count, std::uint8_t* out) const;

private:
    const Volume& m_labels;
    std::unique_ptr<LabelLookup> m_lookup;
};

/// Per voxel: 0 for /transfer, i + 1 for the first entry of `transfers` that
/// lists the voxel's label. At most 255 entries.
LabelBytes classLayers(const Volume& labels, const std::vector<LabelTransfer>& transfers);

/// Per voxel: 1 where the label is one of `ids`, else 0.
LabelBytes labelIndicator(const Volume& labels, const std::vector<std::int64_t>& ids);

/// Per voxel, the texel of the classification texture when a frame writes
/// label channels (/output/aovs "label", /output/mattes; the shaders'
/// classTexel): its classification layer (classLayers) in bits 0-7, its
/// matte (1 + its index in `mattes`, 0 none) in bits 8-11 and its label's
/// code (the id less the lowest id of the volume, plus 1) in bits 12-31.
/// Keeps a reference to `labels`.
class LabelChannelTexels {
public:
    /// Throws InputError when the volume's ids span more than the codes hold.
    LabelChannelTexels(const Volume& labels, const std::vector<LabelTransfer>& transfers,
                       const std::vector<Matte>& mattes);
    /// The texels of voxels [first, first + count), x fastest.
    void write(std::size_t first, std::size_t count, std::uint32_t* out) const;
    /// The volume's lowest label id: code c is label lowest() + c - 1.
    std::int64_t lowest() const { return m_lowest; }

private:
    const Volume& m_labels;
    LabelBytes m_layers, m_mattes;
    std::int64_t m_lowest = 0;
};

/// The segment of interest of a segment alignment (`spec.alignment`), a byte
/// per voxel, 1 inside: the voxels of `scan` whose value lies in its range,
/// or whose label in `labels` is one of its labels. Keeps references to both.
class SegmentIndicator {
public:
    /// Throws InputError naming the operator when it asks for labels and
    /// `labels` is null.
    SegmentIndicator(const OperatorSpec& spec, const Volume& scan, const Volume* labels);
    /// The bytes of voxels [first, first + count), x fastest.
    void write(std::size_t first, std::size_t count, std::uint8_t* out);
    /// Throws InputError naming the operator when no voxel written so far was
    /// inside: the operator would have nothing to keep in place.
    void checkNotEmpty() const;

private:
    const OperatorSpec& m_spec;
    const Volume& m_scan;
    std::optional<LabelBytes> m_labels;
    bool m_any = false;
};

} // namespace cutaway::render

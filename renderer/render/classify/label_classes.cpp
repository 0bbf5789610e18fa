#include "render/classify/label_classes.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace cutaway::render {

// Maps label ids to bytes: a dense table over the ids that occur when their
// span is small (FreeSurfer ids reach ~14000), a hash map otherwise.
class LabelLookup {
public:
    LabelLookup(const Volume& labels, std::unordered_map<std::int64_t, std::uint8_t> map)
        : m_map(std::move(map)) {
        const ValueRange range = valueRange(labels);
        m_lo = static_cast<std::int64_t>(std::llround(range.min));
        const std::int64_t span = static_cast<std::int64_t>(std::llround(range.max)) - m_lo + 1;
        if (span > 0 && span <= (1 << 24)) {
            m_dense.assign(static_cast<std::size_t>(span), 0);
            for (const auto& [id, value] : m_map) {
                if (id >= m_lo && id - m_lo < span)
                    m_dense[static_cast<std::size_t>(id - m_lo)] = value;
            }
        }
    }
    std::uint8_t operator()(double raw) const {
        const std::int64_t id = static_cast<std::int64_t>(std::llround(raw));
        if (!m_dense.empty()) {
            const std::int64_t at = id - m_lo;
            return at >= 0 && at < static_cast<std::int64_t>(m_dense.size())
                       ? m_dense[static_cast<std::size_t>(at)]
                       : 0;
        }
        const auto found = m_map.find(id);
        return found == m_map.end() ? 0 : found->second;
    }

private:
    std::unordered_map<std::int64_t, std::uint8_t> m_map;
    std::int64_t m_lo = 0;
    std::vector<std::uint8_t> m_dense;
};

LabelBytes::LabelBytes(const Volume& labels, std::unordered_map<std::int64_t, std::uint8_t> map)
    : m_labels(labels), m_lookup(std::make_unique<LabelLookup>(labels, std::move(map))) {}

LabelBytes::~LabelBytes() = default;
LabelBytes::LabelBytes(LabelBytes&&) noexcept = default;

void LabelBytes::write(std::size_t first, std::size_t count, std::uint8_t* out) const {
    for (std::size_t j = 0; j < count; ++j)
        out[j] = (*m_lookup)(m_labels.value(first + j));
}

LabelBytes classLayers(const Volume& labels, const std::vector<LabelTransfer>& transfers) {
    std::unordered_map<std::int64_t, std::uint8_t> map;
    const std::size_t count = std::min<std::size_t>(transfers.size(), 255);
    for (std::size_t i = 0; i < count; ++i) {
        for (const std::int64_t id : transfers[i].ids)
            map.emplace(id, static_cast<std::uint8_t>(i + 1)); // the first entry wins
    }
    return LabelBytes(labels, std::move(map));
}

LabelBytes labelIndicator(const Volume& labels, const std::vector<std::int64_t>& ids) {
    std::unordered_map<std::int64_t, std::uint8_t> map;
    for (const std::int64_t id : ids)
        map[id] = 1;
    return LabelBytes(labels, std::move(map));
}

namespace {

// A matte's slot (1 + its index) per label id.
std::unordered_map<std::int64_t, std::uint8_t> matteSlots(const std::vector<Matte>& mattes) {
    std::unordered_map<std::int64_t, std::uint8_t> map;
    for (std::size_t i = 0; i < mattes.size(); ++i)
        map.emplace(mattes[i].id, static_cast<std::uint8_t>(i + 1));
    return map;
}

} // namespace

LabelChannelTexels::LabelChannelTexels(const Volume& labels,
                                       const std::vector<LabelTransfer>& transfers,
                                       const std::vector<Matte>& mattes)
    : m_labels(labels), m_layers(classLayers(labels, transfers)),
      m_mattes(labels, matteSlots(mattes)) {
    const ValueRange range = valueRange(labels);
    m_lowest = static_cast<std::int64_t>(std::llround(range.min));
    const double span = std::round(range.max) - std::round(range.min) + 1.0;
    constexpr double kCodes = (1 << 20) - 1; // bits 12-31, 0 reserved for none
    constexpr double kExact = 1 << 24;       // float32 holds every integer up to here
    if (std::abs(range.min) > kExact || std::abs(range.max) > kExact)
        throw InputError("the label volume holds ids beyond +-16777216 (from " +
                         std::to_string(std::llround(range.min)) + " to " +
                         std::to_string(std::llround(range.max)) +
                         "), which the float32 label channel cannot hold exactly");
    if (span > kCodes)
        throw InputError("the label volume's ids span " + std::to_string(std::llround(span)) +
                         " values (from " + std::to_string(m_lowest) +
                         "); the label channels hold at most 1048575");
}

void LabelChannelTexels::write(std::size_t first, std::size_t count, std::uint32_t* out) const {
    std::vector<std::uint8_t> layers(count), mattes(count);
    m_layers.write(first, count, layers.data());
    m_mattes.write(first, count, mattes.data());
    for (std::size_t j = 0; j < count; ++j) {
        const std::int64_t id = std::llround(m_labels.value(first + j));
        const auto code = static_cast<std::uint32_t>(id - m_lowest + 1);
        out[j] = layers[j] | (std::uint32_t(mattes[j]) << 8) | (code << 12);
    }
}

namespace {

// Where a message about an operator's segment points: its alignment in the
// scene file, and its name.
std::string where(const OperatorSpec& spec) {
    return "/operators/" + std::to_string(spec.index) + "/alignment: " + spec.name + ": ";
}

} // namespace

SegmentIndicator::SegmentIndicator(const OperatorSpec& spec, const Volume& scan,
                                   const Volume* labels)
    : m_spec(spec), m_scan(scan) {
    if (spec.alignment.range) return;
    if (!labels) throw InputError(where(spec) + "segment alignment by labels needs a label volume");
    m_labels.emplace(labelIndicator(*labels, spec.alignment.labels));
}

void SegmentIndicator::write(std::size_t first, std::size_t count, std::uint8_t* out) {
    if (m_labels) {
        m_labels->write(first, count, out);
    } else {
        const auto [lo, hi] = *m_spec.alignment.range;
        for (std::size_t j = 0; j < count; ++j) {
            const double v = m_scan.value(first + j);
            out[j] = v >= lo && v <= hi ? 1 : 0;
        }
    }
    for (std::size_t j = 0; j < count && !m_any; ++j)
        m_any = out[j] != 0;
}

void SegmentIndicator::checkNotEmpty() const {
    if (!m_any)
        throw InputError(
            where(m_spec) + "the segment of its alignment is empty (no voxel " +
            (m_spec.alignment.range ? "has a value in the range" : "has one of the labels") + ")");
}

} // namespace cutaway::render

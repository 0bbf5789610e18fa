#include "render/feature_fields.hpp"

#include "core/error.hpp"
#include "render/classify/label_classes.hpp"
#include "volume/otsu.hpp"
#include "volume/segmentation.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <optional>
#include <set>
#include <sstream>

namespace cutaway::render {
namespace {

std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", v);
    return text;
}

} // namespace

FeatureFields::FeatureFields(const gpu::Context& ctx, bool storageImages)
    : m_ctx(ctx), m_baker(ctx), m_rangeBaker(ctx) {
    // Axis alignment's field, bound as a storage image too where the shaders
    // take the storage paths.
    m_none = gpu::createImage(
        ctx, VK_IMAGE_TYPE_3D, bake::kFeatureFieldFormat, {1, 1, 1},
        VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
            (storageImages ? VkImageUsageFlags{VK_IMAGE_USAGE_STORAGE_BIT} : VkImageUsageFlags{0}));
    m_none.layout = bake::kFeatureLayout;
    const uint16_t zero = 0; // one half float
    gpu::uploadImage(ctx, m_none, &zero, sizeof zero, bake::kFeatureLayout,
                     VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                         VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT); // slicing and the ray caster
}

double FeatureFields::threshold(const Alignment& alignment, const GpuVolume& volume) {
    if (alignment.threshold) return *alignment.threshold;
    if (m_serial != volume.serial) m_otsu.reset();
    if (!m_otsu) m_otsu = otsuThreshold(*volume.scan);
    return *m_otsu;
}

FeatureFields::Described FeatureFields::describe(const Alignment& a, const GpuVolume& volume) {
    if (m_serial != volume.serial) { // another volume: nothing kept applies
        m_fields.clear();
        m_otsu.reset();
        m_serial = volume.serial;
    }
    FieldKey key{a.mode, 0.0, 0.0, std::nullopt, {}};
    std::string note;
    if (a.mode == AlignmentMode::Surface) {
        key.threshold = threshold(a, volume);
        note = "distance field of the object above " + number(key.threshold) +
               (a.threshold ? "" : " (Otsu's threshold)");
    } else {
        key.band = a.band;
        if (a.range) {
            key.range = a.range;
            note = "segment mask of values in [" + number((*a.range)[0]) + ", " +
                   number((*a.range)[1]) + "]";
        } else {
            key.labels = a.labels;
            note = "segment mask of labels";
            for (const std::int64_t id : a.labels)
                note += ' ' + std::to_string(id);
        }
    }
    return {std::move(key), note};
}

void FeatureFields::keepOnly(const std::vector<OperatorSpec>& specs, const GpuVolume& volume) {
    std::set<FieldKey> wanted;
    for (const OperatorSpec& spec : specs)
        if (spec.alignment.mode != AlignmentMode::Axis)
            wanted.insert(describe(spec.alignment, volume).key);
    std::erase_if(m_fields, [&](const auto& field) { return !wanted.count(field.first); });
    m_inUse.clear(); // a new frame
}

gpu::Image FeatureFields::indicatorTexture(const OperatorSpec& spec,
                                           const GpuVolume& volume) const {
    // Written into the upload's staging a few slices at a time: the indicator
    // is never whole on the host (it would add a byte per voxel to the bake's peak).
    SegmentIndicator segment(spec, *volume.scan, volume.labels.get());
    gpu::Image texture = bake::uploadMask(
        m_ctx, volume.dims, [&](std::size_t first, std::size_t count, std::byte* dst) {
            auto* out = reinterpret_cast<std::uint8_t*>(dst);
            segment.write(first, count, out);
            for (std::size_t j = 0; j < count; ++j)
                out[j] = out[j] ? 255 : 0; // R8_UNORM 1 inside
        });
    segment.checkNotEmpty();
    return texture;
}

const gpu::Image& FeatureFields::fieldFor(const OperatorSpec& spec, const GpuVolume& volume,
                                          std::uint64_t* id) {
    const Alignment& a = spec.alignment;
    if (id) *id = 0;
    if (a.mode == AlignmentMode::Axis) return m_none;
    const auto [k, note] = describe(a, volume);
    const std::string inUse = spec.name + ": " + note;
    if (std::find(m_inUse.begin(), m_inUse.end(), inUse) == m_inUse.end()) m_inUse.push_back(inUse);
    auto found = m_fields.find(k);
    if (found != m_fields.end()) {
        if (id) *id = found->second.id;
        return found->second.image;
    }

    const auto start = std::chrono::steady_clock::now();
    gpu::Image field;
    if (a.mode == AlignmentMode::Surface) {
        // The object: above the threshold, or enclosed by it (segmentation.hpp).
        // (The mask on the host is freed before the bake: it is peak memory.)
        const gpu::Image objectTexture =
            bake::uploadMask(m_ctx, objectMask(*volume.scan, threshold(a, volume)), volume.dims);
        field = m_baker.distanceField(objectTexture, volume.spacing, 0.5f);
    } else {
        field = m_baker.segmentMask(indicatorTexture(spec, volume), volume.spacing, a.band);
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    char took[32];
    std::snprintf(took, sizeof took, "%.2f", seconds);
    m_notes.push_back(inUse + ", baked in " + took + " s");
    ++m_bakes;
    // The ranges' steps: DT in half millimetres, up to 63.5 mm (a deeper tau
    // falls back to the bricks: FieldRanges::resolves); M in hundredths.
    const float rangeScale = a.mode == AlignmentMode::Surface ? 2.0f : 100.0f;
    const Field& made =
        m_fields.emplace(k, Field{std::move(field), m_nextId++, rangeScale, std::nullopt})
            .first->second;
    if (id) *id = made.id;
    return made.image;
}

const bake::FieldRanges* FeatureFields::rangesOf(std::uint64_t id, int cellVoxels) {
    for (auto& [key, field] : m_fields) {
        if (field.id != id) continue;
        if (!field.ranges || field.ranges->cellVoxels != cellVoxels)
            field.ranges = m_rangeBaker.ranges(field.image, cellVoxels, field.rangeScale);
        return &*field.ranges;
    }
    return nullptr;
}

std::vector<std::string> FeatureFields::takeNotes() {
    return std::exchange(m_notes, {});
}

} // namespace cutaway::render

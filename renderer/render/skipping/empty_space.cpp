#include "render/skipping/empty_space.hpp"

#include "render/classify/transfer_table.hpp"
#include "render/skipping/operator_regions.hpp"
#include "render/skipping/ray_cells.hpp"
#include "shared/operator_frame.h"

#include <algorithm>
#include <cstring>

namespace cutaway::render {

EmptySpace::EmptySpace(const gpu::Context& ctx, FeatureFields& features)
    : m_ctx(ctx), m_features(features) {}

void EmptySpace::updateSpans(const GpuVolume& volume, int marginVoxels) {
    // One pass over the scan per volume, window and margin; a new
    // classification only re-flags the cells.
    const SpanKey key{volume.serial, volume.window, marginVoxels};
    if (m_spanKey == key) return;
    m_cellSpans.reset();
    m_brickSpans.reset();
    if (volume.scan) {
        m_cellSpans = spanGrid(*volume.scan, volume.window, kRayCellVoxels, 1 + marginVoxels);
        m_brickSpans = brickSpans(*m_cellSpans);
    }
    m_spanKey = key;
}

void EmptySpace::update(const Scene& scene, const GpuVolume& volume, int marginVoxels,
                        std::size_t operators) {
    if (m_regions.size() > operators) m_regions.resize(operators);
    updateSpans(volume, marginVoxels);
    const std::vector<const TransferFunction*> transfers =
        classifyingTransfers(scene, volume.labels != nullptr);
    const bool preintegrated = scene.render.classification == Classification::Preintegrated;
    OccupancyKey key{*m_spanKey, preintegrated, {}};
    for (const TransferFunction* tf : transfers) {
        auto& opacities = key.opacities.emplace_back();
        for (const TransferPoint& p : tf->points)
            opacities.emplace_back(p.value, p.alpha);
    }
    if (m_occupancyKey == key) return;
    m_visible.emplace(transfers, volume.window, preintegrated);
    m_occupancy = m_brickSpans
                      ? brickOccupancy(*m_brickSpans, volume.box, volume.spacing, *m_visible)
                      : fullOccupancy(volume.box);
    m_occupied = m_occupancy.boxes();
    m_occupancyKey = std::move(key);
    ++m_occupancySerial;
}

EmptySpace::Regions& EmptySpace::regionsFor(std::size_t index, const GpuOperator& op,
                                            double reachMm) {
    // The occupancy, the feature field and the mask's threshold, the map and
    // where it lies.
    const Alignment& alignment = op.spec.alignment;
    RegionKey key{m_occupancySerial, reachMm, op.fieldId,          alignmentCode(alignment.mode),
                  alignment.depth,   {},      op.box.localToWorld, op.box.local,
                  op.spec.resolution};
    std::memcpy(key.params.data(), &op.spec.params, sizeof op.spec.params);
    if (m_regions.size() <= index) m_regions.resize(index + 1);
    Regions& r = m_regions[index];
    if (!(r.key == key)) r = Regions{key, std::nullopt, {}};
    return r;
}

const std::vector<operators::LocalBox>&
EmptySpace::regionBoxes(std::size_t index, const GpuOperator& op, double reachMm) {
    Regions& r = regionsFor(index, op, reachMm);
    if (!r.boxes) r.boxes = operatorRegions(op.spec, op.box, m_occupancy, reachMm); // feature-blind
    return *r.boxes;
}

const CaseOccupancy& EmptySpace::casesFor(const GpuOperator& op) {
    const Alignment& a = op.spec.alignment;
    const bool surface = a.mode == AlignmentMode::Surface;
    const double threshold = surface ? a.depth : 0.5;
    const CaseKey key{m_occupancySerial, op.fieldId, threshold, alignmentCode(a.mode)};
    const auto found = m_cases.find(key);
    if (found != m_cases.end()) return found->second;
    // Those of an older occupancy are stale; a sequence that changes the
    // fields or thresholds as it goes keeps no more than a few.
    std::erase_if(m_cases,
                  [&](const auto& c) { return c.first.occupancySerial != m_occupancySerial; });
    if (m_cases.size() >= 2 * CW_RAY_MAX_OPERATORS) m_cases.clear();
    if (a.mode == AlignmentMode::Axis)
        return m_cases.emplace(key, CaseOccupancy::movedOnly(m_occupancy)).first->second;
    const SpanGrid* cells = cellSpans();
    const bake::FieldRanges* ranges =
        cells ? m_features.rangesOf(op.fieldId, cells->cellVoxels) : nullptr;
    return m_cases
        .emplace(key,
                 CaseOccupancy::withFeature(m_occupancy, cells, m_visible ? &*m_visible : nullptr,
                                            ranges, threshold, !surface))
        .first->second;
}

gpu::Image EmptySpace::distanceImage(glm::ivec3 dims, const std::vector<uint8_t>& active) const {
    const std::vector<uint8_t> d = chessboardDistance(dims, active);
    const glm::uvec3 n(dims);
    return gpu::createStorageVolume(m_ctx, VK_FORMAT_R8_UINT, {n.x, n.y, n.z}, d.data(), d.size(),
                                    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
}

VkImageView EmptySpace::blockDistances(std::size_t index, const GpuOperator& op, double reachMm) {
    if (!m_operatorSkipping) { // one active block over the whole box
        if (!m_noSkipping.image) m_noSkipping = distanceImage(glm::ivec3(1), {1});
        return m_noSkipping.view.get();
    }
    Regions& regions = regionsFor(index, op, reachMm);
    if (!regions.distance.image) {
        const OperatorBlocks blocks = operatorBlocks(op.spec, op.box, casesFor(op), reachMm);
        regions.distance = distanceImage(blocks.dims, blocks.active);
    }
    return regions.distance.view.get();
}

} // namespace cutaway::render

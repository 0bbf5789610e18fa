#include "job/export_volume.hpp"

#include "bake/feature_bake.hpp"
#include "job/render_job.hpp"
#include "operators/operator_geometry.hpp"
#include "render/label_classes.hpp"
#include "volume/otsu.hpp"
#include "volume/segmentation.hpp"

#include <memory>

namespace cutaway::job {

std::vector<float> featureFieldCpu(const Volume& volume, const Volume* labels,
                                   const OperatorSpec& op) {
    const Alignment& a = op.alignment;
    if (a.mode == AlignmentMode::Surface) {
        const double threshold = a.threshold ? *a.threshold : otsuThreshold(volume);
        return bake::distanceFieldCpu(objectMask(volume, threshold), volume.dims, volume.spacing);
    }
    if (a.mode != AlignmentMode::Segment) return {};
    render::SegmentIndicator segment(op, volume, labels);
    std::vector<std::uint8_t> indicator(volume.voxelCount());
    segment.write(0, indicator.size(), indicator.data());
    segment.checkNotEmpty();
    return bake::smoothMaskCpu(indicator, volume.dims, volume.spacing, a.band);
}

Volume exportVolume(const Scene& scene) {
    Volume scan = loadSceneVolume(scene);
    const float empty = static_cast<float>(valueRange(scan).min);
    // Under sequential composition with several operators the parser allows
    // no labels (the scan is resampled); with one, it is separate composition.
    const bool sequential =
        scene.render.composition == Composition::Sequential && scene.operators.size() > 1;
    bool byLabels = false;
    for (const OperatorSpec& op : scene.operators)
        byLabels = byLabels || (op.alignment.mode == AlignmentMode::Segment && !op.alignment.range);
    const std::shared_ptr<const Volume> labels =
        byLabels && !sequential ? loadSceneLabels(scene, std::make_shared<const Volume>(scan))
                                : nullptr;
    const auto fieldFor = [&](const Volume& volume, const OperatorSpec& op) {
        return featureFieldCpu(volume, labels.get(), op);
    };
    const operators::PlacedVolume placed = operators::centred(std::move(scan));
    if (sequential)
        return operators::resampleSequentially(placed, scene.operators, empty, fieldFor).volume;
    operators::checkNoOverlap(scene.operators);
    return operators::resampleDeformed(placed, scene.operators, empty, fieldFor).volume;
}

} // namespace cutaway::job

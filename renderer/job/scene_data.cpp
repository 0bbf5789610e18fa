#include "job/scene_data.hpp"

#include "core/error.hpp"
#include "job/volume_frame.hpp"
#include "operators/deformed_volume.hpp"
#include "volume/dicom.hpp"
#include "volume/phantom.hpp"

#include <algorithm>
#include <cstring>
#include <optional>
#include <set>
#include <sstream>

namespace cutaway::job {

Volume loadSceneVolume(const Scene& scene, std::size_t* nonFinite) {
    const VolumeSource& src = scene.volume;
    Volume volume;
    if (!src.phantom.empty())
        volume = makePhantom(src.phantom, src.phantomSize).values;
    else if (src.raw)
        volume = readRaw(src.file, *src.raw);
    else if (!src.series.empty())
        volume = readDicom(src.file, src.series);
    else
        volume = readVolume(src.file);
    if (src.spacing) volume.spacing = *src.spacing;
    // After the value range (which leaves them out) is known: the window and
    // empty space's value come from the finite voxels.
    const std::size_t replaced = replaceNonFinite(volume, emptyValue(scene, volume));
    if (nonFinite) *nonFinite = replaced;
    return volume;
}

std::string nonFiniteWarning(const Scene& scene, std::size_t count, std::size_t voxels) {
    return "/volume/file: " + scene.volume.file.string() + ": " +
           (count == voxels ? "all " + std::to_string(count) + " voxels are"
            : count == 1    ? "1 voxel is"
                            : std::to_string(count) + " voxels are") +
           " not finite (NaN or infinite): left out of the value range and the automatic "
           "window, rendered as empty";
}

namespace {

// Checks labels (read or made) against the scan's grid; see loadSceneLabels.
void checkLabels(const Scene& scene, const Volume& labels, const Volume& scan) {
    const LabelSource& src = *scene.labels;
    const std::string name =
        src.phantom ? "the " + scene.volume.phantom + " phantom's labels" : src.file.string();
    const auto text = [](auto v) {
        std::ostringstream out;
        out << v.x << " x " << v.y << " x " << v.z;
        return out.str();
    };
    if (labels.dims != scan.dims)
        throw InputError(name + ": the label volume's grid is " + text(labels.dims) +
                         " voxels, the scan's " + text(scan.dims) +
                         "; labels must be on the scan's grid");
    const glm::dvec3 ratio = labels.spacing / scan.spacing;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(ratio[a] - 1.0) > 1e-3)
            throw InputError(name + ": the label volume's spacing is " + text(labels.spacing) +
                             " mm, the scan's " + text(scan.spacing) +
                             " mm; labels must be on the scan's grid");
    }
    if (labels.type == VoxelType::F32 || labels.type == VoxelType::F64 || labels.slope != 1.0 ||
        labels.inter != 0.0)
        throw InputError(name + ": label ids must be stored as integers (got " +
                         std::string(voxelTypeName(labels.type)) +
                         (labels.slope != 1.0 || labels.inter != 0.0 ? " with scaling" : "") + ")");
    if (valueRange(labels).min < 0.0) throw InputError(name + ": label ids must not be negative");
}

std::shared_ptr<const Volume> checkedLabels(const Scene& scene, Volume read, const Volume& scan) {
    auto labels = std::make_shared<Volume>(std::move(read));
    if (scene.volume.spacing) labels->spacing = *scene.volume.spacing;
    checkLabels(scene, *labels, scan);
    return labels;
}

// Whether /labels names the file /volume reads (as a volume file, not raw).
bool labelsAreTheScan(const Scene& scene) {
    if (!scene.labels || scene.labels->phantom || !scene.volume.phantom.empty() || scene.volume.raw)
        return false;
    std::error_code ec;
    return std::filesystem::equivalent(scene.labels->file, scene.volume.file, ec) && !ec;
}

} // namespace

std::shared_ptr<const Volume> loadSceneLabels(const Scene& scene,
                                              const std::shared_ptr<const Volume>& scan) {
    if (!scene.labels) return nullptr;
    if (labelsAreTheScan(scene)) {
        checkLabels(scene, *scan, *scan);
        return scan;
    }
    return checkedLabels(scene,
                         scene.labels->phantom
                             ? makePhantom(scene.volume.phantom, scene.volume.phantomSize).labels
                             : readVolume(scene.labels->file),
                         *scan);
}

std::vector<std::string> absentLabelWarnings(const Scene& scene, const Volume& labels) {
    std::set<std::int64_t> carried;
    for (std::size_t i = 0; i < labels.voxelCount(); ++i)
        carried.insert(std::int64_t(labels.raw(i)));
    std::vector<std::string> warnings;
    const auto check = [&](const std::vector<std::int64_t>& ids, const std::string& pointer) {
        for (const std::int64_t id : ids)
            if (!carried.contains(id))
                warnings.push_back(pointer + ": label " + std::to_string(id) +
                                   " is carried by no voxel of the label volume");
    };
    for (std::size_t i = 0; i < scene.labelTransfers.size(); ++i)
        check(scene.labelTransfers[i].ids, "/transfer/labels/" + std::to_string(i) + "/labels");
    for (std::size_t i = 0; i < scene.operators.size(); ++i)
        check(scene.operators[i].alignment.labels,
              "/operators/" + std::to_string(i) + "/alignment/labels");
    return warnings;
}

bake::ValueWindow sceneWindow(const Scene& scene, const Volume& volume) {
    return sceneWindow(scene, valueRange(volume));
}

bake::ValueWindow sceneWindow(const Scene& scene, ValueRange range) {
    if (scene.volume.window) {
        const auto [lo, hi] = *scene.volume.window;
        bake::ValueWindow w{lo, hi};
        if (range.min < lo) w.below = range.min;
        if (range.max > hi) w.above = range.max;
        return w;
    }
    if (range.max > range.min) return {range.min, range.max};
    return {range.min, range.min + 1.0};
}

float emptyValue(const Scene& scene, const Volume& scan) {
    return static_cast<float>(std::min(sceneWindow(scene, scan).lo, valueRange(scan).min));
}

bool sequential(const Scene& scene) {
    return scene.render.composition == Composition::Sequential && scene.operators.size() > 1;
}

FrameVolume frameVolume(const Scene& scene) {
    // A phantom with its own labels is generated once, for both.
    std::optional<Volume> phantomLabels;
    Volume scan;
    std::size_t nonFinite = 0;
    if (scene.labels && scene.labels->phantom && !sequential(scene)) {
        Phantom phantom = makePhantom(scene.volume.phantom, scene.volume.phantomSize);
        scan = std::move(phantom.values);
        if (scene.volume.spacing) scan.spacing = *scene.volume.spacing;
        phantomLabels = std::move(phantom.labels);
    } else {
        scan = loadSceneVolume(scene, &nonFinite);
    }
    const bake::ValueWindow window = sceneWindow(scene, scan);
    const float empty = sequential(scene) ? emptyValue(scene, scan) : 0.0f;
    Volume geometry = geometryOf(scan);
    operators::PlacedVolume placed = operators::centred(std::move(scan));
    if (sequential(scene)) {
        const Scene framed = inVolumeFrame(scene, geometry);
        const std::vector<OperatorSpec> baked(framed.operators.begin(), framed.operators.end() - 1);
        placed = operators::resampleSequentially(placed, baked, empty);
    }
    auto shared = std::make_shared<const Volume>(std::move(placed.volume));
    // Sequential composition with several operators resamples the scan but
    // not its labels, which no longer match it: the frame has none (the
    // parser refuses what would need them).
    std::shared_ptr<const Volume> labels =
        sequential(scene) ? nullptr
        : phantomLabels   ? checkedLabels(scene, std::move(*phantomLabels), *shared)
                          : loadSceneLabels(scene, shared);
    return FrameVolume{std::move(shared), placed.worldLo, window,
                       std::move(labels), nonFinite,      std::move(geometry)};
}

FrameVolumeKey frameVolumeKey(const Scene& scene) {
    // Built from the parsed scene, not its JSON, so scenes made in code work too.
    FrameVolumeKey key;
    key.volume = scene.volume;
    if (scene.labels) {
        key.labels = true;
        key.labelsFile = scene.labels->file;
        key.labelsPhantom = scene.labels->phantom;
    }
    if (sequential(scene)) { // the operators baked into the intermediate volume
        for (std::size_t i = 0; i + 1 < scene.operators.size(); ++i) {
            const OperatorSpec& op = scene.operators[i];
            std::array<float, 12>& params = key.bakedParams.emplace_back();
            static_assert(sizeof op.params == sizeof params);
            std::memcpy(params.data(), &op.params, sizeof params);
            key.bakedPlacements.push_back(op.localToWorld);
            key.bakedSpaces.push_back(op.space);
        }
    }
    return key;
}

std::vector<OperatorSpec> liveOperators(const Scene& scene) {
    if (!sequential(scene)) return scene.operators;
    return {scene.operators.back()};
}

} // namespace cutaway::job

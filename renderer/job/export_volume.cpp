#include "job/export_volume.hpp"

#include "bake/feature_bake.hpp"
#include "core/error.hpp"
#include "job/output_paths.hpp"
#include "job/render_job.hpp"
#include "job/scene_check.hpp"
#include "job/sequence.hpp"
#include "job/volume_frame.hpp"
#include "operators/operator_geometry.hpp"
#include "render/classify/label_classes.hpp"
#include "volume/otsu.hpp"
#include "volume/segmentation.hpp"
#include "volume/volume.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
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

Exported exportVolume(const Scene& given, bool withLabels, int oversample) {
    if (withLabels && !given.labels) throw InputError("the scene has no /labels to export");
    std::size_t nonFinite = 0;
    auto scan = std::make_shared<Volume>(loadSceneVolume(given, &nonFinite));
    const Scene scene = inVolumeFrame(given, *scan); // placements in LPS or RAS placed
    Exported result;
    result.sourceType = scan->type;
    result.sourceSlope = scan->slope;
    result.sourceInter = scan->inter;
    const auto codes = scan->niftiCodes;
    if (nonFinite > 0)
        result.warnings.push_back(nonFiniteWarning(scene, nonFinite, scan->voxelCount()));
    const float empty = emptyValue(scene, *scan);
    const bool resamplesSequentially = sequential(scene);
    // Segments by labels: the parser allows them only where the operator
    // applies to the scan itself (not under sequential composition).
    bool byLabels = false;
    for (const OperatorSpec& op : scene.operators)
        byLabels = byLabels || (op.alignment.mode == AlignmentMode::Segment && !op.alignment.range);
    const std::shared_ptr<const Volume> labels =
        byLabels || withLabels ? loadSceneLabels(scene, scan) : nullptr;
    // Each operator's field is made once, from the volume it applies to (the
    // scan, or under sequential composition what the operators before it
    // left), and read again for the labels, whose grids are the scan's.
    std::map<const OperatorSpec*, operators::FeatureField> fields;
    const auto fieldFor = [&](const Volume& volume, const OperatorSpec& op) {
        operators::FeatureField& field = fields[&op];
        if (!field)
            field = std::make_shared<const std::vector<float>>(
                featureFieldCpu(volume, labels.get(), op));
        return field;
    };
    // Where labels classify the render, a segment's voxels never move.
    const bool classifiedByLabels = scene.labels && !scene.labelTransfers.empty();
    const auto deform = [&](const operators::PlacedVolume& in, float emptyValue,
                            operators::Sampling sampling) {
        const operators::Resampling how{sampling, classifiedByLabels, oversample};
        return resamplesSequentially
                   ? operators::resampleSequentially(in, scene.operators, emptyValue, fieldFor, how)
                   : operators::resampleDeformed(in, scene.operators, emptyValue, fieldFor, how);
    };
    if (!resamplesSequentially) operators::checkNoOverlap(scene.operators);
    // The scan moves into place unless it is also the label volume.
    const operators::PlacedVolume placed =
        operators::centred(labels.get() == scan.get() ? Volume(*scan) : std::move(*scan));
    scan.reset();
    for (OperatorOutside& o :
         operatorsOutside(scene, placed.worldLo, placed.worldLo + placed.volume.extent()))
        result.warnings.push_back(std::move(o.message));
    result.volume = deform(placed, empty, operators::Sampling::Trilinear).volume;
    result.volume.niftiCodes = codes;
    if (withLabels) {
        // On the scan's grid exactly (loadSceneLabels allows spacings 0.1 %
        // apart, and the render ignores origins and directions), so that every
        // step's grid and feature field are the scan's and the two files
        // overlay: the labels take the scan's geometry, whatever their file says.
        operators::PlacedVolume labelled{*labels, placed.worldLo};
        labelled.volume.spacing = placed.volume.spacing;
        labelled.volume.origin = placed.volume.origin;
        labelled.volume.direction = placed.volume.direction;
        labelled.volume.space = placed.volume.space;
        result.labels = deform(labelled, 0.0f, operators::Sampling::Nearest).volume;
        result.labels->niftiCodes = codes;
    }
    return result;
}

namespace {

enum class ExportFormat { None, Nrrd, Nifti, NiftiGzip };

// The format `path` names, in any case, as volumes are read.
ExportFormat formatOf(const std::filesystem::path& path) {
    std::string name = path.filename().string();
    std::transform(name.begin(), name.end(), name.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (name.ends_with(".nrrd")) return ExportFormat::Nrrd;
    if (name.ends_with(".nii")) return ExportFormat::Nifti;
    if (name.ends_with(".nii.gz")) return ExportFormat::NiftiGzip;
    return ExportFormat::None;
}

void checkName(const std::string& option, const std::filesystem::path& path, bool compress) {
    const ExportFormat format = formatOf(path);
    if (format == ExportFormat::None)
        throw InputError(option + " " + path.string() +
                         ": expected a .nrrd, .nii or .nii.gz file name");
    if (format == ExportFormat::NiftiGzip && !compress)
        throw InputError(option + " " + path.string() +
                         ": --raw asks for no compression, and .nii.gz is gzip: name it .nii");
}

} // namespace

void checkExportName(const ExportRequest& request) {
    checkName("-o", request.output, request.compress);
}

void checkExportRequest(const Scene& scene, const std::string& sceneName,
                        const ExportRequest& request) {
    if (request.labelsOutput) checkName("--labels-output", *request.labelsOutput, request.compress);
    if (request.labelsOutput && !scene.labels)
        throw InputError("--labels-output " + request.labelsOutput->string() + ": " + sceneName +
                         " has no /labels");
    checkExportPaths(scene, request.output, request.labelsOutput);
}

std::optional<Volume> storedAs(const Exported& exported, VoxelType type) {
    const Volume& in = exported.volume;
    const bool integer = type != VoxelType::F32 && type != VoxelType::F64;
    const double slope = integer ? exported.sourceSlope : 1.0;
    const double inter = integer ? exported.sourceInter : 0.0;
    Volume out = Volume::allocate(in.dims, type, in.spacing);
    out.origin = in.origin, out.direction = in.direction, out.space = in.space;
    out.niftiCodes = in.niftiCodes;
    out.slope = slope, out.inter = inter;
    const auto [lo, hi] = storedRange(type);
    for (std::size_t i = 0; i < in.voxelCount(); ++i) {
        double raw = (in.value(i) - inter) / slope;
        if (integer) raw = std::round(raw);
        if (!(raw >= lo && raw <= hi)) return std::nullopt;
        out.setRaw(i, raw);
    }
    return out;
}

void writeExport(const Exported& exported, const ExportRequest& request,
                 const std::function<void(const std::filesystem::path&, const Volume&)>& wrote) {
    const auto write = [&](const std::filesystem::path& path, const Volume& v) {
        createOutputFolder(path); // as `render` does
        if (formatOf(path) == ExportFormat::Nrrd)
            writeNrrd(path, v, request.compress);
        else
            writeNifti(path, v); // gzip or not by its name
        if (wrote) wrote(path, v);
    };
    // The scan's own type where the values fit it, or the one asked for.
    // NRRD has no standard scaling (ParaView and Slicer would read the raw
    // numbers), so a scaled scan goes to NRRD as float32 unless asked.
    const bool scaled = exported.sourceSlope != 1.0 || exported.sourceInter != 0.0;
    const VoxelType type = request.type ? *request.type
                           : scaled && formatOf(request.output) == ExportFormat::Nrrd
                               ? VoxelType::F32
                               : exported.sourceType;
    std::optional<Volume> typed =
        type == VoxelType::F32 ? std::optional<Volume>() : storedAs(exported, type);
    if (!typed && request.type && type != VoxelType::F32)
        throw InputError("--type " + std::string(voxelTypeName(type)) +
                         ": the deformed volume holds values that " +
                         std::string(voxelTypeName(type)) + " cannot hold");
    write(request.output, typed ? *typed : exported.volume);
    if (!exported.labels || !request.labelsOutput) return;
    try {
        write(*request.labelsOutput, *exported.labels);
    } catch (...) { // both files or neither
        std::error_code ignored;
        std::filesystem::remove(request.output, ignored);
        throw;
    }
}

} // namespace cutaway::job

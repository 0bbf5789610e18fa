#include "dataset_bench.hpp"

#include "bake/feature_ranges.hpp"
#include "bake/feature_region.hpp"
#include "bake/operator_bake.hpp"
#include "baton.hpp"
#include "bench_util.hpp"
#include "core/error.hpp"
#include "job/render_job.hpp"
#include "operators/operator_geometry.hpp"
#include "render/classify/transfer_table.hpp"
#include "render/feature_fields.hpp"
#include "render/skipping/ray_cells.hpp"
#include "scene/scene.hpp"
#include "vtk_spec.hpp"

#include <cstdio>
#include <fstream>

namespace cutaway::bench {

std::vector<SceneSetting> rowSettings(const DatasetEntry& entry, const std::string& alignment,
                                      double spacing, const BenchOptions& o) {
    // Whole slabs (refine 1): a row's samples are then the slicing planes'
    // crossings, the paper's work and the work VTK's ray caster is given.
    std::vector<SceneSetting> settings{
        {"/render/slice_spacing", spacing},
        {"/render/refine", 1},
        {"/render/size", nlohmann::json::array({o.width, o.height})},
        {"/render/shading/enabled", true},
    };
    const nlohmann::json& a = entry.alignments.at(alignment);
    if (a.is_null())
        settings.push_back({"/operators", nlohmann::json::array()});
    else
        settings.push_back({"/operators/0/alignment", a});
    settings.insert(settings.end(), o.extra.begin(), o.extra.end());
    return settings;
}

namespace {

// What a dataset costs before its first frame, each the median of a few runs:
// reading, the upload, the gradients, and for the operator of the Table 1
// rows its distance field (surface), segment mask (segment) and map. The
// feature bakes go through the renderer's own cache, fresh each run, so they
// include the CPU steps (Otsu, flood fill, label indicator) a user waits for.
nlohmann::json bakeTimes(const gpu::Context& ctx, const DatasetEntry& entry,
                         const BenchOptions& o) {
    nlohmann::json bakes;
    const Scene base = loadScene(entry.scene);
    std::shared_ptr<const Volume> volume, labels;
    bakes["read_ms"] = medianMs(1, [&] {
        volume = std::make_shared<const Volume>(job::loadSceneVolume(base));
        labels = job::loadSceneLabels(base, volume);
    });
    const Volume& scan = *volume;
    const bake::ValueWindow window = job::sceneWindow(base, scan);
    bake::GradientBaker gradients(ctx);
    gpu::Image values;
    bakes["upload_ms"] = medianMs(o.bakeRepeats, [&] {
        values = gpu::Image{};
        values = bake::uploadVolume(ctx, scan, window);
    });
    bakes["gradients_ms"] = medianMs(o.bakeRepeats, [&] { gradients.bake(values, scan.spacing); });
    values = gpu::Image{};
    const render::GpuVolume gv =
        render::prepareVolume(ctx, gradients, volume, window, std::nullopt, labels);
    const auto featureMs = [&](const std::string& alignment) {
        if (!entry.alignments.count(alignment)) return nlohmann::json();
        const Scene s = loadScene(entry.scene, rowSettings(entry, alignment, 1.0, o));
        return nlohmann::json(medianMs(o.bakeRepeats, [&] {
            render::FeatureFields fields(ctx);
            fields.fieldFor(s.operators.at(0), gv);
        }));
    };
    // Empty space: the span pass over the scan (once per volume, window and
    // margin; the margin of d = 1) and what a new transfer function costs
    // after it: the bricks' and cells' flags and the cells' distances.
    const int margin = render::slabMargin(1.0);
    render::SpanGrid cellSpans, bricks;
    bakes["value_spans_ms"] = medianMs(o.bakeRepeats, [&] {
        cellSpans = render::spanGrid(scan, window, render::kRayCellVoxels, 1 + margin);
        bricks = render::brickSpans(cellSpans);
    });
    bakes["classify_ms"] = medianMs(o.bakeRepeats, [&] {
        const render::VisibleValues visible(
            render::classifyingTransfers(base, labels != nullptr), window,
            base.render.classification == Classification::Preintegrated);
        (void)render::brickOccupancy(bricks, gv.box, scan.spacing, visible);
        (void)render::rayCells(cellSpans, visible);
    });
    bakes["distance_field_ms"] = featureMs("surface");
    if (entry.alignments.count("surface")) {
        // The distance field's ranges over the ray caster's cells, which its
        // operator's empty-space skipping reads (bake/feature_ranges.hpp),
        // once per field.
        const Scene s = loadScene(entry.scene, rowSettings(entry, "surface", 1.0, o));
        render::FeatureFields fields(ctx);
        const gpu::Image& field = fields.fieldFor(s.operators.at(0), gv);
        const bake::FieldRangeBaker ranges(ctx);
        bakes["field_ranges_ms"] = medianMs(o.bakeRepeats, [&] {
            (void)ranges.ranges(field, render::kRayCellVoxels, 2.0f); // steps of 0.5 mm
        });
    }
    bakes["segment_mask_ms"] = featureMs("segment");
    if (entry.alignments.count("segment")) {
        // What moving a segment-aligned operator costs: its region of the
        // mask and of the values moving material reads (bake/feature_region).
        const Scene s = loadScene(entry.scene, rowSettings(entry, "segment", 1.0, o));
        const OperatorSpec& op = s.operators.at(0);
        render::FeatureFields fields(ctx);
        const gpu::Image& mask = fields.fieldFor(op, gv);
        const operators::WorldBox box = operators::worldBox(op);
        const bake::VoxelRegion region =
            bake::regionCovering(gv.dims, gv.spacing, gv.box.lo, box.lo(), box.hi());
        const bake::FeatureRegionBaker regions(ctx);
        bakes["segment_region_ms"] =
            medianMs(o.bakeRepeats, [&] { regions.bake(gv.values, mask, region); });
        bakes["segment_region_voxels"] = {region.size.x, region.size.y, region.size.z};
    }
    if (!base.operators.empty()) {
        const OperatorSpec& op = base.operators[0];
        const operators::LocalBox box = operators::deformedBounds(op.params, op.resolution);
        bake::OperatorBaker baker(ctx);
        bakes["operator_map_ms"] = medianMs(o.bakeRepeats, [&] {
            baker.bake(op.params, glm::vec3(box.lo), glm::vec3(box.hi), op.resolution);
        });
        bakes["operator_map_texels"] = {op.resolution.x, op.resolution.y, op.resolution.z};
    }
    return bakes;
}

} // namespace

std::vector<DatasetEntry> readTable(const std::filesystem::path& file) {
    std::ifstream in(file);
    if (!in) throw InputError(file.string() + ": cannot open the benchmark table");
    const nlohmann::json doc = nlohmann::json::parse(in);
    std::vector<DatasetEntry> entries;
    for (const auto& d : doc.at("datasets")) {
        DatasetEntry e;
        e.dataset = d.at("dataset").get<std::string>();
        e.scene = file.parent_path() / d.at("scene").get<std::string>();
        for (const auto& [name, alignment] : d.at("alignments").items())
            e.alignments[name] = alignment;
        entries.push_back(std::move(e));
    }
    return entries;
}

namespace {

// The samples of one ray-cast frame of `scene`, by kind, summed over its
// pixels (VolumeRenderer::setCensus).
nlohmann::json censusOf(job::FrameRenderer& renderer, const Scene& scene) {
    renderer.setCensus(true);
    const Image counts = renderer.render(scene);
    renderer.setCensus(false);
    double sums[4] = {0.0, 0.0, 0.0, 0.0};
    for (std::size_t i = 0; i < counts.rgba.size(); ++i)
        sums[i % 4] += counts.rgba[i];
    return {{"volume_fetched", sums[0]},
            {"volume_shaded", sums[1]},
            {"operator_resolved", sums[2]},
            {"operator_shaded", sums[3]}};
}

} // namespace

nlohmann::json renderPeak(const gpu::Context& ctx, const DatasetEntry& entry,
                          const std::string& alignment, const std::string& method, double spacing,
                          const BenchOptions& o) {
    std::vector<SceneSetting> settings = rowSettings(entry, alignment, spacing, o);
    settings.push_back({"/render/method", method});
    const Scene scene = loadScene(entry.scene, settings);
    (void)job::FrameRenderer(ctx).render(scene);
    return {{"peak_rss_mib", peakRssMiB()}};
}

nlohmann::json benchDataset(const gpu::Context& ctx, const DatasetEntry& entry,
                            const BenchOptions& o) {
    Scene base;
    try {
        base = loadScene(entry.scene);
    } catch (const InputError& e) {
        return {{"skipped", e.what()}};
    }
    // With another process taking turns, the scan's loading and the bakes are
    // a turn of their own: they would slow the other's frames.
    Baton baton(o.batonFile, o.batonId, o.batonSlice);
    baton.acquire();
    const nlohmann::json bakes = o.bakeRepeats > 0 ? bakeTimes(ctx, entry, o) : nlohmann::json();
    // The bake timings above keep extra copies; the peak that matters is a
    // render's: from here on, as `cutaway render` would hold it.
    const double bakePeak = peakRssMiB();
    const bool reset = resetPeakRss();
    ctx.resetMemoryPeak();
    double scanMiB = 0.0;
    nlohmann::json dims;
    VtkSpec vtk(entry.dataset, base, o);
    {
        const Volume scan = job::loadSceneVolume(base); // freed before the frames
        scanMiB = double(scan.data.size()) / (1024.0 * 1024.0);
        dims = {scan.dims.x, scan.dims.y, scan.dims.z};
        vtk.setVolume(scan, job::sceneWindow(base, scan));
    }

    nlohmann::json records = nlohmann::json::array();
    job::FrameRenderer renderer(ctx);
    for (const std::string& alignment : o.alignments) {
        if (!entry.alignments.count(alignment)) continue;
        for (const std::string& method : o.methods) {
            for (const double spacing : o.spacings) {
                std::vector<SceneSetting> settings = rowSettings(entry, alignment, spacing, o);
                settings.push_back({"/render/method", method});
                Scene scene = loadScene(entry.scene, settings);
                const double azimuth = scene.camera.azimuthDeg;
                baton.acquire();
                const double firstMs = millisecondsOf([&] { renderer.render(scene); });
                baton.release();
                std::vector<double> ms, starts;
                for (int i = 1; i <= o.frames; ++i) {
                    scene.camera.azimuthDeg = azimuth + 360.0 * i / o.frames;
                    baton.acquire();
                    starts.push_back(steadySeconds());
                    ms.push_back(millisecondsOf([&] { renderer.render(scene); }));
                    baton.release();
                    if (alignment == "none" && method == "slicing") vtk.addCamera(scene, spacing);
                }
                const Stats s = statsOf(ms);
                nlohmann::json r;
                r["renderer"] = "cutaway";
                r["device"] = ctx.deviceName();
                r["dataset"] = entry.dataset;
                r["dims"] = dims;
                r["alignment"] = alignment;
                r["method"] = method;
                r["operator"] =
                    scene.operators.empty()
                        ? "none"
                        : scene.document.at("operators").at(0).at("type").get<std::string>();
                r["width"] = o.width;
                r["height"] = o.height;
                r["slice_spacing"] = spacing;
                r["frames"] = o.frames;
                r["ms_median"] = s.median;
                r["ms_min"] = s.min;
                r["ms_max"] = s.max;
                r["fps"] = 1000.0 / s.median;
                r["first_frame_ms"] = firstMs;
                // Each frame's time, in view order: bench/ab_interleave.py pairs two
                // builds' frames by view.
                r["frame_ms"] = ms;
                // Taking turns, where each frame started (CLOCK_MONOTONIC
                // seconds): the other process's frames lie between them.
                if (!o.batonFile.empty()) r["frame_start_s"] = starts;
                if (o.census && method == "raycast") {
                    scene.camera.azimuthDeg = azimuth;
                    r["census"] = censusOf(renderer, scene);
                    std::fprintf(stderr, "    census per frame: %s\n", r["census"].dump().c_str());
                }
                records.push_back(r);
                std::fprintf(stderr,
                             "  %-12s %-8s %-8s d=%.1f  %8.1f ms median  (first %7.1f ms)\n",
                             entry.dataset.c_str(), alignment.c_str(), method.c_str(), spacing,
                             s.median, firstMs);
            }
        }
    }
    baton.handOver();
    if (!o.vtkDir.empty()) vtk.write(o.vtkDir);
    const double peak = peakRssMiB();
    const double devicePeak = double(ctx.memoryPeak()) / (1024.0 * 1024.0);
    for (auto& r : records) {
        r["device_peak_mib"] = devicePeak;
        if (!bakes.is_null()) r["bake_ms"] = bakes;
        r["scan_mib"] = scanMiB;
        r["peak_rss_mib"] = reset ? nlohmann::json(peak) : nlohmann::json();
        r["bake_bench_peak_rss_mib"] = bakePeak;
        r["memory_goal_mib"] = 4.0 * scanMiB + 300.0;
    }
    return {{"records", records}};
}

} // namespace cutaway::bench

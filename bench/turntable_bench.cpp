#include "turntable_bench.hpp"

#include "bench_util.hpp"
#include "job/render_job.hpp"
#include "job/sequence.hpp"

#include <algorithm>
#include <cstdio>

namespace cutaway::bench {

namespace {

// The single-frame rate of `scene` as the Table 1 rows take it (a warm-up
// frame, then `frames` with the view turning), in a renderer of its own.
double singleFrameFps(const gpu::Context& ctx, Scene scene, int frames) {
    job::FrameRenderer renderer(ctx);
    const double azimuth = scene.camera.azimuthDeg;
    renderer.render(scene);
    std::vector<double> ms;
    for (int i = 1; i <= frames; ++i) {
        scene.camera.azimuthDeg = azimuth + 360.0 * i / frames;
        ms.push_back(millisecondsOf([&] { renderer.render(scene); }));
    }
    return 1000.0 / statsOf(ms).median;
}

} // namespace

nlohmann::json benchTurntable(const gpu::Context& ctx, const std::vector<DatasetEntry>& entries,
                              const std::vector<std::string>& only, const BenchOptions& o,
                              int frames) {
    for (const DatasetEntry& entry : entries) {
        if (!only.empty() && std::find(only.begin(), only.end(), entry.dataset) == only.end())
            continue;
        if (!entry.alignments.count("surface")) continue;
        const std::filesystem::path dir =
            std::filesystem::temp_directory_path() / ("cutaway_turntable_" + entry.dataset);
        std::vector<SceneSetting> settings = rowSettings(entry, "surface", 1.0, o);
        settings.push_back(
            {"/animation",
             {{"frames", {0, frames - 1}},
              {"tracks",
               {{{"target", "/camera/orbit/azimuth"},
                 {"interpolation", "linear"},
                 {"keys",
                  {{{"frame", 0}, {"value", 0}}, {{"frame", frames}, {"value", 360}}}}}}}}});
        settings.push_back({"/output/png", true});
        Scene scene;
        try {
            scene = loadScene(entry.scene, settings);
        } catch (const std::exception&) {
            continue; // its scan is absent: try the next dataset
        }
        job::SequenceOptions options;
        options.overrides.outputPattern = (dir / "frame_####.exr").string();
        std::fprintf(stderr, "turntable: %s, %d frames to %s\n", entry.dataset.c_str(), frames,
                     dir.c_str());
        // Single frames just before and just after: the machine's speed
        // drifts over minutes, so the rows timed earlier are no yardstick.
        const double singleBefore = singleFrameFps(ctx, scene, o.frames);
        const job::SequenceSummary summary = job::renderSequence(ctx, scene, options);
        const double singleAfter = singleFrameFps(ctx, scene, o.frames);
        std::filesystem::remove_all(dir);
        std::vector<double> ms;
        for (const double s : summary.frameSeconds)
            ms.push_back(1000.0 * s);
        const Stats s = statsOf(ms);
        // From the first frame's files to the last's: the rate once the scan
        // is loaded and baked (the single-frame rows leave those out too).
        const std::vector<double>& done = summary.doneSeconds;
        const double steadyFps =
            done.size() > 1 ? double(done.size() - 1) / (done.back() - done.front()) : 0.0;
        return {{"renderer", "cutaway"},
                {"kind", "turntable"},
                {"dataset", entry.dataset},
                {"alignment", "surface"},
                {"method", scene.render.method == RenderMethod::Raycast ? "raycast" : "slicing"},
                {"width", o.width},
                {"height", o.height},
                {"slice_spacing", 1.0},
                {"frames", summary.rendered},
                {"failed", summary.failed},
                {"total_s", summary.totalSeconds},
                {"sustained_fps", summary.rendered / summary.totalSeconds},
                {"steady_fps", steadyFps},
                {"first_frame_s", done.empty() ? 0.0 : done.front()},
                {"frame_ms_median", s.median},
                {"single_fps_before", singleBefore},
                {"single_fps_after", singleAfter},
                {"writes", "EXR (half) + PNG per frame"}};
    }
    return {{"skipped", "no dataset with a surface row is present"}};
}

void printTurntable(const nlohmann::json& records) {
    for (const nlohmann::json& t : records) {
        if (t.value("kind", "") != "turntable") continue;
        double single = 0.0;
        for (const nlohmann::json& r : records) {
            if (r.value("kind", "") != "turntable" && r["dataset"] == t["dataset"] &&
                r["alignment"] == "surface" && r["slice_spacing"] == 1.0 &&
                r.value("method", "slicing") == t.value("method", "slicing"))
                single = r["fps"].get<double>();
        }
        std::printf(
            "\nturntable (%s, surface, %s, d = 1.0, %d frames written as %s): %.1f s in all "
            "(%.2f fps), the first frame's files after %.1f s (loading and bakes), "
            "%.2f fps sustained from there; single frames: %.2f fps in the table, "
            "%.2f just before and %.2f just after the turntable\n",
            t["dataset"].get<std::string>().c_str(), t.value("method", "slicing").c_str(),
            t["frames"].get<int>(), t["writes"].get<std::string>().c_str(),
            t["total_s"].get<double>(), t["sustained_fps"].get<double>(),
            t["first_frame_s"].get<double>(), t["steady_fps"].get<double>(), single,
            t.value("single_fps_before", 0.0), t.value("single_fps_after", 0.0));
    }
}

} // namespace cutaway::bench

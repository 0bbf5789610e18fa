#include "turntable_bench.hpp"

#include "bench_util.hpp"
#include "io/exr.hpp"
#include "io/png.hpp"
#include "job/render_job.hpp"
#include "job/sequence.hpp"

#include <algorithm>
#include <cstdio>
#include <future>
#include <string>
#include <utility>

namespace cutaway::bench {

namespace {

// The single-frame rate of `scene` over the turntable's own `views` views
// (azimuth + 360 i / views), rendered one by one with no files, in a
// renderer of its own after a warm-up frame: the views' count over their
// total time, the same statistic as the turntable's sustained rate (a
// median of a few views is not: the views differ in cost); `last` receives
// the last frame.
double singleFrameFps(const gpu::Context& ctx, Scene scene, int views, Image* last = nullptr) {
    job::FrameRenderer renderer(ctx);
    const double azimuth = scene.camera.azimuthDeg;
    renderer.render(scene);
    const double ms = millisecondsOf([&] {
        for (int i = 1; i <= views; ++i) {
            scene.camera.azimuthDeg = azimuth + 360.0 * i / views;
            Image image = renderer.render(scene);
            if (last) *last = std::move(image);
        }
    });
    return 1000.0 * views / ms;
}

// What a frame's files cost the next frame's render, without the drift of
// the machine's speed (which moves the turntable's rate against single frames
// rendered a minute apart by 5-10 %): each of the turntable's `views` views is
// rendered twice in a row, alone and while the previous image's files are
// written as a sequence writes them (job::writeFrameFiles), the order turning
// with the view. A render with files counts until its files are written.
nlohmann::json interleavedWrites(const gpu::Context& ctx, Scene scene, int views,
                                 const std::filesystem::path& dir) {
    job::FrameRenderer renderer(ctx);
    const double azimuth = scene.camera.azimuthDeg;
    Image previous = renderer.render(scene);
    double alone = 0.0, withFiles = 0.0;
    ExrOptions exr;
    exr.attributes = {{"cutaway/frame", "0"}};
    for (int i = 1; i <= views; ++i) {
        scene.camera.azimuthDeg = azimuth + 360.0 * i / views;
        for (int k = 0; k < 2; ++k) {
            const bool write = (i + k) % 2 == 1;
            Image image;
            Image written = write ? previous : Image(); // moved in, as a sequence does
            const double ms = millisecondsOf([&] {
                if (!write) {
                    image = renderer.render(scene);
                    return;
                }
                std::future<double> files = job::writeFrameFiles(
                    dir / "interleaved.exr", dir / "interleaved.png", std::move(written), exr);
                image = renderer.render(scene);
                files.get();
            });
            (write ? withFiles : alone) += ms;
            previous = std::move(image);
        }
    }
    return {{"views", views}, {"ms_alone", alone}, {"ms_with_files", withFiles}};
}

// What writing `image` costs, as a frame of a sequence is written (half
// floats), with each of /output/compression's choices, and as the PNG
// preview: the median of 5 writes into `dir`, and the file's size.
nlohmann::json writeCosts(const Image& image, const std::filesystem::path& dir) {
    const std::pair<const char*, ExrCompression> kCompressions[] = {{"none", ExrCompression::None},
                                                                    {"rle", ExrCompression::Rle},
                                                                    {"zips", ExrCompression::Zips},
                                                                    {"zip", ExrCompression::Zip},
                                                                    {"piz", ExrCompression::Piz}};
    nlohmann::json costs = nlohmann::json::array();
    auto time = [&](const std::string& file, const auto& write) {
        const std::filesystem::path path = dir / file;
        std::vector<double> ms;
        for (int i = 0; i < 5; ++i)
            ms.push_back(millisecondsOf([&] { write(path); }));
        costs.push_back({{"file", file},
                         {"ms_median", statsOf(ms).median},
                         {"bytes", std::filesystem::file_size(path)}});
    };
    for (const auto& [name, compression] : kCompressions) {
        ExrOptions options;
        options.compression = compression;
        time(std::string("frame_") + name + ".exr",
             [&](const std::filesystem::path& path) { writeExr(path, image, options); });
    }
    time("frame.png", [&](const std::filesystem::path& path) { writePng(path, image); });
    return costs;
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
        const double singleBefore = singleFrameFps(ctx, scene, frames);
        const job::SequenceSummary summary = job::renderSequence(ctx, scene, options);
        Image last;
        const double singleAfter = singleFrameFps(ctx, scene, frames, &last);
        const nlohmann::json writes = writeCosts(last, dir);
        const nlohmann::json interleaved = interleavedWrites(ctx, scene, frames, dir);
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
                {"last_frame_s", done.empty() ? 0.0 : done.back()},
                {"frame_ms_median", s.median},
                {"single_fps_before", singleBefore},
                {"single_fps_after", singleAfter},
                {"single_views", frames}, // the turntable's views, count over total time
                {"writes", "EXR (half) + PNG per frame"},
                {"write_costs", writes},
                {"interleaved", interleaved}};
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
            "%.2f fps sustained from there; single frames: %.2f fps in the table (the median "
            "view), its views one by one without files %.2f fps just before and %.2f just "
            "after the turntable\n",
            t["dataset"].get<std::string>().c_str(), t.value("method", "slicing").c_str(),
            t["frames"].get<int>(), t["writes"].get<std::string>().c_str(),
            t["total_s"].get<double>(), t["sustained_fps"].get<double>(),
            t["first_frame_s"].get<double>(), t["steady_fps"].get<double>(), single,
            t.value("single_fps_before", 0.0), t.value("single_fps_after", 0.0));
        if (t.contains("interleaved")) {
            const nlohmann::json& w = t["interleaved"];
            const double alone = w["ms_alone"].get<double>();
            std::printf("its %d views each rendered alone and again while the previous frame's "
                        "files are written, in turns: %.0f against %.0f ms (%.3f)\n",
                        w["views"].get<int>(), alone, w["ms_with_files"].get<double>(),
                        alone / w["ms_with_files"].get<double>());
        }
        if (!t.contains("write_costs")) continue;
        std::printf("\nwriting one %dx%d frame (half floats; each the median of 5 writes):\n\n"
                    "| file | ms | KiB |\n|---|---|---|\n",
                    t["width"].get<int>(), t["height"].get<int>());
        for (const nlohmann::json& w : t["write_costs"])
            std::printf("| %s | %.1f | %.0f |\n", w["file"].get<std::string>().c_str(),
                        w["ms_median"].get<double>(), w["bytes"].get<double>() / 1024.0);
    }
}

} // namespace cutaway::bench

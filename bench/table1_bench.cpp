// The paper's Table 1 benchmark (docs/performance.md#how-to-measure): 512x512 frames, slice
// spacing 1.0 and 0.5, shading on, one operator aligned four ways (none, axis,
// surface, segment) on each dataset of bench/table1.json; the bake times and
// peak memory of each dataset; and a 36-frame turntable written to disk.
// Each dataset runs in a child process of its own so its peak memory is its
// own. Prints tables and writes bench/results.json; asserts nothing.
#include "baton.hpp"
#include "bench_util.hpp"
#include "core/error.hpp"
#include "core/process_memory.hpp"
#include "dataset_bench.hpp"
#include "turntable_bench.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

using namespace cutaway;
using nlohmann::json;

namespace {

// Runs `body` in a child process with a Vulkan context of its own and returns
// the JSON it produced (or {"error": ...}).
json inChild(const std::function<json(const gpu::Context&)>& body) {
    char path[] = "/tmp/cutaway_bench_XXXXXX";
    const int fd = mkstemp(path);
    if (fd < 0) return {{"error", "cannot make a temporary file"}};
    close(fd);
    std::fflush(nullptr);
    const pid_t pid = fork();
    if (pid == 0) {
        bench::resetPeakRss(); // from what the child inherited
        json out;
        try {
            gpu::Context ctx(gpu::ContextOptions{});
            out = body(ctx);
        } catch (const std::exception& e) {
            out = {{"error", e.what()}};
        }
        std::ofstream(path) << out.dump();
        std::fflush(nullptr);
        _exit(0);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    std::remove(path);
    if (!WIFEXITED(status) || text.str().empty())
        return {{"error", "the benchmark process died (status " + std::to_string(status) + ")"}};
    return json::parse(text.str());
}

std::string dimsText(const json& d) {
    return std::to_string(d[0].get<int>()) + "x" + std::to_string(d[1].get<int>()) + "x" +
           std::to_string(d[2].get<int>());
}

std::string msText(const json& v) {
    if (v.is_null()) return "-";
    char text[32];
    std::snprintf(text, sizeof text, "%.0f", v.get<double>());
    return text;
}

void printFrames(const json& records) {
    std::printf("\n| dataset | dims | alignment | operator | method | d | median ms | min ms | max "
                "ms | fps | first frame ms |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const json& r : records) {
        if (r.value("kind", "") == "turntable") continue;
        std::printf(
            "| %s | %s | %s | %s | %s | %.1f | %.1f | %.1f | %.1f | %.2f | %.0f |\n",
            r["dataset"].get<std::string>().c_str(), dimsText(r["dims"]).c_str(),
            r["alignment"].get<std::string>().c_str(), r["operator"].get<std::string>().c_str(),
            r["method"].get<std::string>().c_str(), r["slice_spacing"].get<double>(),
            r["ms_median"].get<double>(), r["ms_min"].get<double>(), r["ms_max"].get<double>(),
            r["fps"].get<double>(), r["first_frame_ms"].get<double>());
    }
}

void printBakes(const json& records) {
    std::printf(
        "\n| dataset | read ms | upload ms | gradients ms | distance field ms | its ranges ms | "
        "segment "
        "mask ms | segment region ms | operator map ms | value spans ms | new transfer ms | peak "
        "RSS MiB, one "
        "render (largest row) | peak RSS MiB, whole run | of it Vulkan MiB | goal MiB (4 x scan "
        "+ 300) |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    std::string last;
    for (const json& r : records) {
        if (r.value("kind", "") == "turntable" || !r.contains("bake_ms") || r["dataset"] == last)
            continue;
        last = r["dataset"];
        const json& b = r["bake_ms"];
        std::printf("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %.0f | %.0f | %.0f | "
                    "%.0f |\n",
                    last.c_str(), msText(b["read_ms"]).c_str(), msText(b["upload_ms"]).c_str(),
                    msText(b["gradients_ms"]).c_str(),
                    msText(b.value("distance_field_ms", json())).c_str(),
                    msText(b.value("field_ranges_ms", json())).c_str(),
                    msText(b.value("segment_mask_ms", json())).c_str(),
                    msText(b.value("segment_region_ms", json())).c_str(),
                    msText(b.value("operator_map_ms", json())).c_str(),
                    msText(b.value("value_spans_ms", json())).c_str(),
                    msText(b.value("classify_ms", json())).c_str(),
                    r.value("render_peak_rss_mib_largest", 0.0),
                    r["peak_rss_mib"].is_number() ? r["peak_rss_mib"].get<double>() : 0.0,
                    r.value("device_peak_mib", 0.0), r["memory_goal_mib"].get<double>());
    }
}

std::vector<std::string> split(const std::string& text) {
    std::vector<std::string> parts;
    std::stringstream in(text);
    for (std::string part; std::getline(in, part, ',');)
        if (!part.empty()) parts.push_back(part);
    return parts;
}

} // namespace

int main(int argc, char** argv) {
    cutaway::unmapLargeBlocksWhenFreed();
    CLI::App app{"cutaway's Table 1 benchmark: frame times, bake times, peak memory"};
    std::string table = "bench/table1.json", output = "bench/results.json", vtkDir, datasets,
                alignments, spacings = "1.0,0.5";
    bench::BenchOptions o;
    int turntableFrames = 36;
    app.add_option("--table", table, "Datasets and their Table 1 rows");
    app.add_option("--json", output, "Where to write the records");
    app.add_option("--vtk-dir", vtkDir, "Write the VTK comparison's specs here");
    app.add_option("--datasets", datasets, "Only these datasets (comma-separated)");
    app.add_option("--alignments", alignments, "Only these rows: none,axis,surface,segment");
    app.add_option("--spacings", spacings, "Slice spacings d (comma-separated)");
    std::string methods = "slicing,raycast";
    app.add_option("--methods", methods, "render.method of the rows: slicing,raycast");
    app.add_option("--frames", o.frames, "Timed frames per row, after one warm-up")
        ->check(CLI::Range(1, 1000));
    app.add_option("--size", o.width, "Image width and height")->check(CLI::Range(16, 4096));
    app.add_option("--turntable", turntableFrames, "Frames of the written turntable (0: none)")
        ->check(CLI::Range(0, 360));
    app.add_option("--bake-repeats", o.bakeRepeats,
                   "Runs of each bake timing (0: no bake timings, frames only)")
        ->check(CLI::Range(0, 100));
    std::vector<std::string> sets;
    app.add_option(
        "--baton", o.batonFile,
        "Take turns with another benchmark process through this file (ab_interleave.py)");
    app.add_option("--baton-id", o.batonId, "This process's id in the turn-taking")
        ->check(CLI::Range(0, 1));
    app.add_option("--baton-slice", o.batonSlice, "Seconds this process keeps the turn")
        ->check(CLI::PositiveNumber);
    app.add_flag("--census", o.census,
                 "Count the samples of each ray-cast row's first view by kind (record's census)");
    app.add_option("--set", sets, "Override a scene value in every row: /json/pointer=VALUE");
    CLI11_PARSE(app, argc, argv);
    for (const std::string& s : sets) {
        const auto eq = s.find('=');
        if (eq == std::string::npos) {
            std::fprintf(stderr, "cutaway_bench: --set %s: expected /json/pointer=VALUE\n",
                         s.c_str());
            return 2;
        }
        const std::string value = s.substr(eq + 1);
        o.extra.push_back({s.substr(0, eq), nlohmann::json::accept(value)
                                                ? nlohmann::json::parse(value)
                                                : nlohmann::json(value)});
    }
    o.height = o.width;
    o.vtkDir = vtkDir;
    if (!alignments.empty()) o.alignments = split(alignments);
    o.methods = split(methods);
    o.spacings.clear();
    for (const std::string& s : split(spacings))
        o.spacings.push_back(std::stod(s));

    std::vector<bench::DatasetEntry> entries;
    try {
        entries = bench::readTable(table);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "cutaway_bench: %s\n", e.what());
        return 2;
    }
    const std::vector<std::string> only = split(datasets);
    json records = json::array();
    for (const bench::DatasetEntry& entry : entries) {
        if (!only.empty() && std::find(only.begin(), only.end(), entry.dataset) == only.end())
            continue;
        std::fprintf(stderr, "%s (%s)\n", entry.dataset.c_str(), entry.scene.c_str());
        const json result =
            inChild([&](const gpu::Context& ctx) { return bench::benchDataset(ctx, entry, o); });
        if (result.contains("skipped")) {
            std::fprintf(stderr, "  skipped: %s\n", result["skipped"].get<std::string>().c_str());
            continue;
        }
        if (result.contains("error")) {
            std::fprintf(stderr, "  failed: %s\n", result["error"].get<std::string>().c_str());
            continue;
        }
        // Peak memory of one render per row, each in a process of its own
        // (as `cutaway render`), at the smallest spacing (the most slices);
        // with the bakes, not in frames-only runs (vtk_bench.py's pairing).
        std::map<std::pair<std::string, std::string>, double> renderPeaks;
        double largest = 0.0;
        const double spacing = *std::min_element(o.spacings.begin(), o.spacings.end());
        for (const json& r : o.bakeRepeats > 0 ? result["records"] : json::array()) {
            const auto row =
                std::make_pair(r["alignment"].get<std::string>(), r["method"].get<std::string>());
            if (renderPeaks.count(row)) continue;
            const json peak = inChild([&](const gpu::Context& ctx) {
                return bench::renderPeak(ctx, entry, row.first, row.second, spacing, o);
            });
            renderPeaks[row] = peak.value("peak_rss_mib", 0.0);
            largest = std::max(largest, renderPeaks[row]);
        }
        for (json r : result["records"]) {
            if (!renderPeaks.empty()) {
                r["render_peak_rss_mib"] = renderPeaks[{r["alignment"], r["method"]}];
                r["render_peak_rss_mib_largest"] = largest;
            }
            records.push_back(r);
        }
    }
    bench::Baton(o.batonFile, o.batonId, o.batonSlice).finish(); // the turntable takes no turns
    if (turntableFrames > 0) {
        const json result = inChild([&](const gpu::Context& ctx) {
            return bench::benchTurntable(ctx, entries, only, o, turntableFrames);
        });
        if (result.contains("error"))
            std::fprintf(stderr, "turntable failed: %s\n",
                         result["error"].get<std::string>().c_str());
        else if (!result.is_null() && !result.contains("skipped"))
            records.push_back(result);
    }
    printFrames(records);
    printBakes(records);
    bench::printTurntable(records);
    std::ofstream(output) << records.dump(1) << '\n';
    std::printf("\nrecords: %s\n", output.c_str());
    return 0;
}

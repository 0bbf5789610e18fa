#pragma once
// One dataset of the Table 1 benchmark: its bake times, then per alignment and
// slice spacing a warm-up frame and timed frames with the view rotating (a
// turntable), as records for bench/results.json.
#include "gpu/context.hpp"
#include "scene/scene.hpp"

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace cutaway::bench {

struct BenchOptions {
    int width = 512;
    int height = 512;
    int frames = 5; ///< timed frames per row, after one warm-up
    std::vector<double> spacings{1.0, 0.5};
    std::vector<std::string> alignments{"none", "axis", "surface", "segment"};
    /// render.method of each row; "raycast" only renders the rows without an operator.
    std::vector<std::string> methods{"slicing", "raycast"};
    int bakeRepeats = 3;             ///< runs of each bake timing; 0: none (frames only)
    std::filesystem::path vtkDir;    ///< where to write the VTK comparison's spec; empty = none
    std::vector<SceneSetting> extra; ///< --set overrides applied to every row (experiments)
    /// Ray-cast rows also count their first frame's samples by kind
    /// (VolumeRenderer::setCensus): the record's "census", samples per frame.
    bool census = false;
    /// Turn-taking with another benchmark process (bench/baton.hpp,
    /// bench/ab_interleave.py): the turn's file (empty: none), this process's
    /// id (0 or 1) and the seconds it keeps the turn.
    std::filesystem::path batonFile;
    int batonId = 0;
    double batonSlice = 2.0;
};

/// A row of bench/table1.json: a scene with one operator, and the alignment
/// each Table 1 row gives it (null: the operator removed).
struct DatasetEntry {
    std::string dataset;
    std::filesystem::path scene;
    std::map<std::string, nlohmann::json> alignments;
};

/// The --set overrides that make `entry`'s scene one Table 1 row.
std::vector<SceneSetting> rowSettings(const DatasetEntry& entry, const std::string& alignment,
                                      double spacing, const BenchOptions& options);

/// Reads bench/table1.json; scene paths are resolved against its folder.
std::vector<DatasetEntry> readTable(const std::filesystem::path& file);

/// Renders one frame of a row, as `cutaway render` would, in a process that
/// does nothing else (the caller's child): {"peak_rss_mib": the process's
/// peak resident memory after it}.
nlohmann::json renderPeak(const gpu::Context& ctx, const DatasetEntry& entry,
                          const std::string& alignment, const std::string& method, double spacing,
                          const BenchOptions& options);

/// Runs one dataset. Returns {"records": [...]} with one record per alignment
/// and spacing, each carrying the dataset's bake times and peak memory; or
/// {"skipped": "why"} when the scene's files are absent.
nlohmann::json benchDataset(const gpu::Context& ctx, const DatasetEntry& entry,
                            const BenchOptions& options);

} // namespace cutaway::bench

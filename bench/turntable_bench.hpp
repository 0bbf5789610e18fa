#pragma once
// A turntable written to disk (EXR and PNG per frame) through the same
// sequence runner as `cutaway render`: does the sequence sustain the single
// frame rate, i.e. does writing frame n overlap rendering frame n + 1?
#include "dataset_bench.hpp"

namespace cutaway::bench {

/// Renders `frames` frames of the first dataset of `entries` (among `only`, if
/// given) whose scene is present, its operator surface-aligned, at slice
/// spacing 1.0, into a temporary folder (removed afterwards). Returns a record
/// with "kind": "turntable", or {"skipped": why}.
nlohmann::json benchTurntable(const gpu::Context& ctx, const std::vector<DatasetEntry>& entries,
                              const std::vector<std::string>& only, const BenchOptions& options,
                              int frames);

/// Prints the turntable record beside its dataset's single-frame rate.
void printTurntable(const nlohmann::json& records);

} // namespace cutaway::bench

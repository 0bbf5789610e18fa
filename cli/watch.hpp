#pragma once
// `cutaway watch SCENE [-o preview.png]`: its options and its loop.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace cutaway::cli {

struct WatchArgs {
    std::string scene;
    std::string output; ///< empty: job::defaultPreviewPath
    std::string size;
    std::vector<std::string> sets;
    std::string device;
    double poll = 0.1; ///< seconds between looks at the files
};

CLI::App* addWatch(CLI::App& app, WatchArgs& args);
/// Renders a preview, then again after each change, until a signal.
int runWatch(const WatchArgs& args);

} // namespace cutaway::cli

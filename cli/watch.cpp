#include "watch.hpp"

#include "arguments.hpp"
#include "core/error.hpp"
#include "interrupt.hpp"
#include "job/sequence.hpp"
#include "job/watch.hpp"
#include "scene/animation.hpp"

#include <chrono>
#include <cstdio>
#include <thread>

namespace cutaway::cli {

CLI::App* addWatch(CLI::App& app, WatchArgs& args) {
    CLI::App* watch = app.add_subcommand(
        "watch", "Render a draft preview of a scene's first frame again whenever the scene or a "
                 "file it reads changes, until Ctrl-C");
    watch->add_option("scene", args.scene, "Scene file (JSON)")->required();
    watch->add_option("-o,--output", args.output,
                      "The preview, a PNG (default: SCENE's folder, its name + _preview.png)");
    watch->add_option("--size", args.size, "Preview size WxH (default: the scene's)");
    watch->add_option("--set", args.sets, "Override a scene value: /json/pointer=VALUE");
    watch->add_option("--device", args.device, "Vulkan device (name or index, see `devices`)");
    watch->add_option("--poll", args.poll, "Seconds between looks at the files (default 0.1)")
        ->check(CLI::Range(0.01, 10.0));
    return watch;
}

namespace {

void report(const job::PreviewResult& r, const std::filesystem::path& output) {
    for (const std::string& w : r.warnings)
        std::fprintf(stderr, "cutaway: warning: %s\n", w.c_str());
    if (r.written)
        std::fprintf(stderr, "cutaway: preview %s updated in %.2f s\n", output.string().c_str(),
                     r.seconds);
    else
        std::fprintf(stderr, "cutaway: error: %s\ncutaway: waiting for the next change\n",
                     r.error.c_str());
    std::fflush(stderr);
}

} // namespace

int runWatch(const WatchArgs& args) {
    job::PreviewRequest request;
    request.scene = args.scene;
    for (const std::string& s : args.sets)
        request.settings.push_back(parseSetting(s));
    request.output = args.output.empty() ? job::defaultPreviewPath(args.scene)
                                         : std::filesystem::path(args.output);
    if (request.output.extension() != ".png")
        throw InputError("-o " + request.output.string() + ": expected a .png file name");
    if (!args.size.empty()) request.size = parseSize(args.size);
    installInterruptHandlers();
    gpu::ContextOptions options;
    options.deviceName = args.device;
    gpu::Context ctx(options);
    job::PreviewRenderer previews(ctx);
    job::FileWatch files;
    files.watch({request.scene});
    std::fprintf(stderr, "cutaway: watching %s; the preview is %s; Ctrl-C stops\n",
                 args.scene.c_str(), request.output.string().c_str());
    const auto pause = std::chrono::duration<double>(args.poll);
    for (bool first = true; interruptSignal() == 0; first = false) {
        if (!first && !files.changed()) {
            std::this_thread::sleep_for(pause);
            continue;
        }
        // An editor may write a file in steps: wait until it holds still.
        if (!first) do
                std::this_thread::sleep_for(pause);
            while (files.changed() && interruptSignal() == 0);
        const job::PreviewResult result = previews.render(request);
        report(result, request.output);
        files.watch(result.inputs);
    }
    std::fprintf(stderr, "cutaway: stopped watching %s\n", args.scene.c_str());
    return 0;
}

} // namespace cutaway::cli

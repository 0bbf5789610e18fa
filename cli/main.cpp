// cutaway: the command line. Argument handling only; the work is in the library.
//
//   cutaway render SCENE [-o PATTERN] [--frames A..B] [--shard I/N] [--size WxH]
//                  [--set /json/pointer=VALUE ...] [--png] [--skip-existing] [--fail-fast]
//                  [--writers N] [--device NAME] [--memory-budget SIZE] [--quiet]
//   cutaway validate SCENE [--set ...]
//   cutaway export SCENE [--frame N] -o OUT.nrrd|.nii[.gz] [--labels-output L] [--set ...]
//                  [--oversample K] [--raw]
//   cutaway watch SCENE [-o preview.png] [--size WxH] [--set ...]
//   cutaway info FILE [--series S]
//   cutaway devices
//
// Exit codes: 0 success, 1 runtime failure, 2 bad input or usage;
// 128 + signal when interrupted by SIGINT, SIGTERM, SIGHUP or SIGQUIT.
#include "arguments.hpp"
#include "core/error.hpp"
#include "core/process_memory.hpp"
#include "gpu/context.hpp"
#include "gpu/memory.hpp"
#include "interrupt.hpp"
#include "job/address_space.hpp"
#include "job/export_volume.hpp"
#include "job/output_paths.hpp"
#include "job/render_job.hpp"
#include "job/scene_check.hpp"
#include "job/sequence.hpp"
#include "job/validate_run.hpp"
#include "progress.hpp"
#include "scene/animation.hpp"
#include "scene/scene.hpp"
#include "volume/child_process.hpp"
#include "volume/dicom.hpp"
#include "volume/read_budget.hpp"
#include "volume/volume.hpp"
#include "volume_info.hpp"
#include "watch.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <regex>
#include <unistd.h>

namespace {

constexpr int kExitRuntime = 1;
constexpr int kExitInput = 2;

struct RenderArgs {
    std::string scene;
    std::string output;
    std::string frames;
    std::string shard;
    std::string size;
    std::vector<std::string> sets;
    std::string device;
    std::string memoryBudget;
    bool png = false;
    bool skipExisting = false;
    bool failFast = false;
    bool quiet = false;
    int writers = 0; ///< 0: the sequence's default (job::writesInFlight)
};

std::vector<cutaway::SceneSetting> parseSettings(const std::vector<std::string>& sets) {
    std::vector<cutaway::SceneSetting> out;
    for (const auto& s : sets)
        out.push_back(cutaway::parseSetting(s));
    return out;
}

// Frames outside /animation/frames render with every track holding its first
// or last key; allowed (a held pose), but rarely what was meant.
void warnOutsideAnimation(const cutaway::Scene& scene, int first, int last, const char* option) {
    const auto& a = scene.animation;
    if (first >= a.firstFrame && last <= a.lastFrame) return;
    std::fprintf(stderr,
                 "cutaway: warning: %s reaches outside the scene's /animation/frames %d..%d; %s\n",
                 option, a.firstFrame, a.lastFrame,
                 a.tracks.empty() ? "the scene has no tracks, so every frame is the same"
                                  : "there every track holds its nearest key");
}

int parseFrame(const std::string& text) {
    static const std::regex number("[0-9]{1,7}");
    if (!std::regex_match(text, number) || std::stoi(text) > cutaway::kMaxFrame)
        throw cutaway::InputError("--frame: expected one frame number in [0, " +
                                  std::to_string(cutaway::kMaxFrame) + "], got \"" + text + "\"");
    return std::stoi(text);
}

// The run that render (and validate) arguments describe.
cutaway::job::SequenceOptions runOptions(const RenderArgs& args, const cutaway::Scene& scene) {
    namespace job = cutaway::job;
    job::SequenceOptions options;
    if (!args.output.empty()) options.overrides.outputPattern = args.output;
    if (!args.size.empty()) options.overrides.size = cutaway::cli::parseSize(args.size);
    options.overrides.png = args.png;
    if (!args.frames.empty()) {
        options.frames = job::parseFrameRange(args.frames);
        if (!args.quiet)
            warnOutsideAnimation(scene, options.frames->first, options.frames->last, "--frames");
    }
    if (!args.shard.empty()) options.shard = job::parseShard(args.shard);
    options.skipExisting = args.skipExisting;
    options.failFast = args.failFast;
    options.writers = args.writers;
    return options;
}

int runRender(const RenderArgs& args) {
    namespace job = cutaway::job;
    // Everything about the input is checked before a device is opened.
    const cutaway::Scene scene = cutaway::loadScene(args.scene, parseSettings(args.sets));
    job::SequenceOptions options = runOptions(args, scene);
    job::checkOutputPaths(scene, options);

    cutaway::cli::installInterruptHandlers();
    cutaway::cli::Progress progress(args.quiet, isatty(STDERR_FILENO) != 0);
    options.onFrame = [&](const job::FrameEvent& e) { progress.frame(e); };
    options.stopRequested = [] { return cutaway::cli::interruptSignal() != 0; };

    // The driver and the image, before the device is made (the volume's
    // share is checked once it is read: job/address_space.hpp).
    cutaway::Scene first = scene;
    job::applyOverrides(first, options.overrides);
    job::checkAddressSpace(job::addressSpaceNeed(first));
    cutaway::gpu::ContextOptions contextOptions;
    contextOptions.deviceName = args.device;
    if (!args.memoryBudget.empty()) {
        try {
            contextOptions.memoryBudget = cutaway::gpu::parseMemorySize(args.memoryBudget);
        } catch (const cutaway::InputError& e) {
            throw cutaway::InputError(std::string("--memory-budget: ") + e.what());
        }
    }
    cutaway::gpu::Context ctx(contextOptions);
    const job::SequenceSummary summary = job::renderSequence(ctx, scene, options);
    progress.summary(summary);

    if (const int sig = cutaway::cli::interruptSignal()) {
        std::fprintf(stderr, "cutaway: interrupted by signal %d; finished frames are whole\n", sig);
        return 128 + sig;
    }
    if (summary.resourceExceeded) {
        std::fprintf(stderr, "cutaway: stopped: the device cannot render this scene (see above); "
                             "finished frames are whole\n");
        if (const auto limit = job::addressSpaceLimit())
            std::fprintf(stderr,
                         "cutaway: note: under an address-space limit (ulimit -v) of %llu KiB\n",
                         static_cast<unsigned long long>(*limit >> 10));
    }
    if (summary.writeFailed) {
        std::fprintf(stderr, "cutaway: stopped: a frame could not be written (see above); "
                             "finished frames are whole, --skip-existing resumes the run\n");
    }
    if (summary.failed) return summary.anyBadInput ? kExitInput : kExitRuntime;
    return 0;
}

struct ExportArgs {
    std::string scene;
    std::string output;
    std::vector<std::string> sets;
    std::string labelsOutput;
    std::string frame;
    int oversample = 1;
    bool raw = false;
    std::string type = "auto";
};

int runExport(const ExportArgs& args) {
    cutaway::job::ExportRequest request{args.output, std::nullopt, !args.raw, args.oversample};
    if (!args.labelsOutput.empty()) request.labelsOutput = args.labelsOutput;
    if (args.type != "auto") request.type = cutaway::parseVoxelType(args.type, "--type");
    cutaway::job::checkExportName(request);
    const cutaway::Scene base = cutaway::loadScene(args.scene, parseSettings(args.sets));
    int frame = base.animation.firstFrame;
    if (!args.frame.empty()) {
        frame = parseFrame(args.frame);
        warnOutsideAnimation(base, frame, frame, "--frame");
    }
    const cutaway::Scene scene = cutaway::sceneAtFrame(base, frame);
    cutaway::job::checkExportRequest(scene, args.scene, request);
    cutaway::cli::installEndingHandlers(); // no temporary outlives a signal
    const cutaway::job::Exported exported = [&] {
        try {
            return cutaway::job::exportVolume(scene, request.labelsOutput.has_value(),
                                              request.oversample);
        } catch (const cutaway::InputError& e) {
            const std::string what = e.what();
            // A JSON pointer is a place in the scene file: name the file too.
            if (!what.starts_with('/')) throw;
            throw cutaway::InputError(args.scene + " (frame " + std::to_string(frame) +
                                      "): " + what);
        }
    }();
    for (const std::string& warning : exported.warnings)
        std::fprintf(stderr, "cutaway: warning: %s: %s\n", args.scene.c_str(), warning.c_str());
    const bool terminal = isatty(STDERR_FILENO) != 0;
    cutaway::job::writeExport(exported, request, [&](const auto& path, const cutaway::Volume& v) {
        if (terminal)
            std::fprintf(stderr, "wrote %s: frame %d, %d x %d x %d %s voxels\n",
                         path.string().c_str(), frame, v.dims.x, v.dims.y, v.dims.z,
                         std::string(cutaway::voxelTypeName(v.type)).c_str());
    });
    return 0;
}

// Checks what `render` with the same arguments would refuse as bad input,
// frame by frame, without a device (job/validate_run.hpp).
int runValidate(const RenderArgs& args) {
    namespace job = cutaway::job;
    const cutaway::Scene scene = cutaway::loadScene(args.scene, parseSettings(args.sets));
    const job::Validation v = job::validateRun(scene, runOptions(args, scene), args.scene);
    if (v.failed > 0) {
        for (const std::string& failure : v.failures)
            std::cerr << "cutaway: error: " << failure << "\n";
        if (v.failed > job::kFailuresShown)
            std::cerr << "cutaway: error: ... and " << v.failed - job::kFailuresShown
                      << " more frame(s)\n";
        std::cerr << "cutaway: " << v.failed << " of " << v.checked << " frames are not valid\n";
        return kExitInput;
    }
    if (!args.quiet)
        for (const std::string& warning : v.warnings)
            std::cerr << "cutaway: warning: " << args.scene << ": " << warning << "\n";
    if (!args.quiet)
        for (const std::string& note : v.notes)
            std::cerr << "cutaway: note: " << args.scene << ": " << note << "\n";
    if (v.framesInRun == 0)
        std::printf("%s: valid (no frames in this run)\n", args.scene.c_str());
    else
        std::printf("%s: valid (%d frame(s), %d..%d)\n", args.scene.c_str(), v.framesInRun,
                    v.firstFrame, v.lastFrame);
    return 0;
}

// A DICOM path lists its series; the one it names (or the only one, or
// --series) is described as any volume is.
int runInfo(const std::string& file, const std::string& series) {
    if (!cutaway::isDicomPath(file)) {
        if (!series.empty())
            throw cutaway::InputError("--series: " + file + " is not a DICOM file or folder");
        std::fputs(cutaway::cli::describeVolume(cutaway::readVolume(file), file).c_str(), stdout);
        return 0;
    }
    const cutaway::DicomListing listing = cutaway::listDicom(file);
    std::printf("%s\n%s", file.c_str(), cutaway::describeSeries(listing).c_str());
    if (series.empty() && listing.series.size() > 1 && listing.namedUid.empty()) {
        std::printf("(give --series NUMBER|UID|DESCRIPTION to describe one)\n");
        return 0;
    }
    std::fputs(cutaway::cli::describeVolume(cutaway::readDicom(file, series), file).c_str(),
               stdout);
    return 0;
}

int runDevices() {
    for (const auto& d : cutaway::gpu::listDevices())
        std::printf("%s\n", d.c_str());
    return 0;
}

// An allocation that failed: its size says little, an address-space limit much.
int outOfMemory() {
    const auto limit = cutaway::job::addressSpaceLimit();
    std::cerr << "cutaway: error: out of memory"
              << (limit ? " under the address-space limit (ulimit -v) of " +
                              std::to_string(*limit >> 10) + " KiB"
                        : std::string())
              << "\n";
    return kExitRuntime;
}

CLI::App* addRender(CLI::App& app, RenderArgs& args) {
    CLI::App* render = app.add_subcommand("render", "Render a scene to EXR frames");
    render->add_option("scene", args.scene, "Scene file (JSON)")->required();
    render->add_option("-o,--output", args.output,
                       "Output pattern, e.g. out/frame_####.exr (#### or %04d: frame number)");
    render->add_option("--frames", args.frames,
                       "Frames A..B (inclusive) or N; default: the scene's /animation/frames");
    render->add_option("--shard", args.shard,
                       "Render only frames f with f mod N == I, e.g. 2/8 (one machine of 8)");
    render->add_option("--size", args.size, "Image size WIDTHxHEIGHT, e.g. 512x512");
    render->add_option("--set", args.sets,
                       "Override a scene value: /json/pointer=VALUE (repeatable), "
                       "e.g. --set /camera/orbit/azimuth=90");
    render->add_flag("--png", args.png, "Also write an sRGB PNG preview per frame");
    render->add_flag("--skip-existing", args.skipExisting,
                     "Leave frames whose output files exist (resume an interrupted run)");
    render->add_flag("--fail-fast", args.failFast,
                     "Stop at the first failed frame (default: render the others, exit non-zero)");
    render
        ->add_option("--writers", args.writers,
                     "Frames whose files are written at once while later frames render "
                     "(default: one per core, up to 8, within 512 MiB of images)")
        ->check(CLI::Range(1, cutaway::job::kMostWritersAllowed));
    render->add_option("--device", args.device,
                       "Vulkan device: a substring of its name (see `cutaway devices`)");
    render->add_option("--memory-budget", args.memoryBudget,
                       "Device memory cutaway may hold at once, e.g. 2G or 512M; past it a "
                       "frame fails naming the limit (default: the device-local heap)");
    render->add_flag("-q,--quiet", args.quiet, "Print nothing but errors");
    return render;
}

CLI::App* addValidate(CLI::App& app, RenderArgs& args) {
    CLI::App* validate = app.add_subcommand(
        "validate", "Check what `render` with the same arguments would refuse: the scene, every "
                    "frame, the output paths and the files it reads; without a device");
    validate->add_option("scene", args.scene, "Scene file (JSON)")->required();
    validate->add_option("-o,--output", args.output, "Output pattern, as for render");
    validate->add_option("--frames", args.frames, "Frames A..B or N, as for render");
    validate->add_option("--shard", args.shard, "I/N, as for render");
    validate->add_option("--size", args.size, "WIDTHxHEIGHT, as for render");
    validate->add_option("--set", args.sets, "Override a scene value: /json/pointer=VALUE");
    validate->add_flag("--png", args.png, "PNG previews, as for render");
    validate->add_flag("-q,--quiet", args.quiet, "Print nothing but errors and the verdict");
    return validate;
}

CLI::App* addExport(CLI::App& app, ExportArgs& args) {
    CLI::App* exportCommand = app.add_subcommand(
        "export", "Write the deformed volume of one frame as NRRD or NIfTI (for ParaView, "
                  "3D Slicer, nibabel); no device needed");
    exportCommand->add_option("scene", args.scene, "Scene file (JSON)")->required();
    exportCommand->add_option("-o,--output", args.output, "Output file: .nrrd, .nii or .nii.gz")
        ->required();
    exportCommand->add_option("--frame", args.frame, "Frame of the animation (default: its first)");
    exportCommand->add_option("--set", args.sets, "Override a scene value: /json/pointer=VALUE");
    exportCommand->add_option(
        "--labels-output", args.labelsOutput,
        "Also write the scene's label volume, deformed alike (.nrrd, .nii, .nii.gz)");
    exportCommand
        ->add_option("--oversample", args.oversample,
                     "A grid K times finer along each axis (1-4, default 1): cut faces alias K "
                     "times less")
        ->check(CLI::Range(1, cutaway::job::kMostOversample));
    exportCommand->add_option("--type", args.type,
                              "Voxel type written: auto (the scan's own where the values fit "
                              "it, else float32; default), uint8, int8, uint16, int16, uint32, "
                              "int32, float32 or float64");
    exportCommand->add_flag("--raw", args.raw,
                            "Raw encoding instead of gzip (NRRD; NIfTI by its name)");
    return exportCommand;
}

CLI::App* addInfo(CLI::App& app, std::string& file, std::string& series) {
    CLI::App* info =
        app.add_subcommand("info", "Describe a volume file (NRRD, NIfTI, MetaImage, DICOM)");
    info->add_option("file", file, "Volume file, or a DICOM folder, DICOMDIR or file")->required();
    info->add_option("--series", series,
                     "The DICOM series to describe: its number, UID or description");
    return info;
}

// --read-budget and --verbose on every subcommand that reads a volume.
void addReadOptions(std::initializer_list<CLI::App*> commands, std::string& budget, bool& verbose) {
    for (CLI::App* command : commands) {
        command->add_option("--read-budget", budget,
                            "Host memory reading a volume may take, e.g. 8G; a volume that "
                            "declares more is refused before it is read (default: half the "
                            "machine's memory)");
        command->add_flag("--verbose", verbose,
                          "Also print the messages of the libraries that read the input "
                          "(GDCM's, for DICOM), escaped");
    }
}

// Sets the read budget `--read-budget` gave, if any.
void applyReadBudget(const std::string& value) {
    if (value.empty()) return;
    try {
        cutaway::setReadBudget(cutaway::gpu::parseMemorySize(value));
    } catch (const cutaway::InputError& e) {
        throw cutaway::InputError(std::string("--read-budget: ") + e.what());
    }
}

} // namespace

int main(int argc, char** argv) {
    cutaway::unmapLargeBlocksWhenFreed();
    cutaway::shareArenasUnderAddressLimit();
    cutaway::cli::ignoreBrokenPipes();
    CLI::App app{"cutaway: illustrative volume manipulation, rendered to EXR"};
    app.require_subcommand(1);
    app.set_version_flag("--version", std::string("cutaway ") + CUTAWAY_VERSION);

    RenderArgs renderArgs, validateArgs;
    ExportArgs exportArgs;
    std::string infoFile, infoSeries;
    CLI::App* render = addRender(app, renderArgs);
    CLI::App* validate = addValidate(app, validateArgs);
    CLI::App* exportCommand = addExport(app, exportArgs);
    CLI::App* info = addInfo(app, infoFile, infoSeries);
    cutaway::cli::WatchArgs watchArgs;
    CLI::App* watch = cutaway::cli::addWatch(app, watchArgs);
    auto* devices = app.add_subcommand("devices", "List the Vulkan devices");
    std::string readBudget;
    bool verbose = false;
    addReadOptions({render, validate, exportCommand, info, watch}, readBudget, verbose);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        return code == 0 ? 0 : kExitInput;
    }

    try {
        applyReadBudget(readBudget);
        cutaway::detail::showChildMessages(verbose);
        if (render->parsed()) return runRender(renderArgs);
        if (validate->parsed()) return runValidate(validateArgs);
        if (exportCommand->parsed()) return runExport(exportArgs);
        if (info->parsed()) return runInfo(infoFile, infoSeries);
        if (watch->parsed()) return cutaway::cli::runWatch(watchArgs);
        if (devices->parsed()) return runDevices();
    } catch (const cutaway::InputError& e) {
        std::cerr << "cutaway: error: " << e.what() << "\n";
        return kExitInput;
    } catch (const std::bad_alloc&) {
        return outOfMemory();
    } catch (const std::exception& e) {
        std::cerr << "cutaway: error: " << e.what() << "\n";
        return kExitRuntime;
    }
    return kExitInput;
}

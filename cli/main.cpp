// cutaway: the command line. Argument handling only; the work is in the library.
//
//   cutaway render SCENE [-o PATTERN] [--size WxH] [--png] [--device NAME] [--quiet]
//   cutaway validate SCENE
//   cutaway info FILE
//   cutaway devices
//
// Exit codes: 0 success, 1 runtime failure, 2 bad input or usage.
#include <cstdio>
#include <iostream>
#include <regex>

#include <CLI/CLI.hpp>

#include "core/error.hpp"
#include "gpu/context.hpp"
#include "job/render_job.hpp"
#include "scene/scene.hpp"
#include "volume/volume.hpp"
#include "volume_info.hpp"

namespace {

constexpr int kExitRuntime = 1;
constexpr int kExitInput = 2;

glm::ivec2 parseSize(const std::string& text) {
    static const std::regex form("([0-9]{1,5})x([0-9]{1,5})");
    std::smatch m;
    if (!std::regex_match(text, m, form))
        throw cutaway::InputError("--size: expected WIDTHxHEIGHT such as 512x512, got \"" + text +
                                  "\"");
    glm::ivec2 size(std::stoi(m[1].str()), std::stoi(m[2].str()));
    if (size.x < 1 || size.y < 1 || size.x > 16384 || size.y > 16384)
        throw cutaway::InputError("--size: each side must be in [1, 16384], got " + text);
    return size;
}

struct RenderArgs {
    std::string scene;
    std::string output;
    std::string size;
    std::string device;
    bool png = false;
    bool quiet = false;
};

int runRender(const RenderArgs& args) {
    cutaway::Scene scene = cutaway::loadScene(args.scene);
    cutaway::job::RenderOverrides overrides;
    if (!args.output.empty()) overrides.outputPattern = args.output;
    if (!args.size.empty()) overrides.size = parseSize(args.size);
    overrides.png = args.png;
    cutaway::job::applyOverrides(scene, overrides);

    cutaway::gpu::ContextOptions options;
    options.deviceName = args.device;
    cutaway::gpu::Context ctx(options);
    if (!args.quiet) std::cerr << "cutaway: rendering on " << ctx.deviceName() << "\n";
    for (const auto& frame : cutaway::job::renderScene(ctx, scene)) {
        if (args.quiet) continue;
        std::printf("wrote %s (%.2f s)\n", frame.exr.string().c_str(), frame.seconds);
        if (frame.png) std::printf("wrote %s\n", frame.png->string().c_str());
    }
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"cutaway: illustrative volume manipulation, rendered to EXR"};
    app.require_subcommand(1);
    app.set_version_flag("--version", std::string("cutaway ") + CUTAWAY_VERSION);

    RenderArgs renderArgs;
    auto* render = app.add_subcommand("render", "Render a scene to EXR frames");
    render->add_option("scene", renderArgs.scene, "Scene file (JSON)")->required();
    render->add_option("-o,--output", renderArgs.output,
                       "Output pattern, e.g. out/frame_####.exr (#### or %04d: frame number)");
    render->add_option("--size", renderArgs.size, "Image size WIDTHxHEIGHT, e.g. 512x512");
    render->add_flag("--png", renderArgs.png, "Also write an sRGB PNG preview per frame");
    render->add_option("--device", renderArgs.device,
                       "Vulkan device: a substring of its name (see `cutaway devices`)");
    render->add_flag("-q,--quiet", renderArgs.quiet, "Print nothing but errors");

    std::string validateScene;
    auto* validate = app.add_subcommand("validate", "Check a scene without rendering");
    validate->add_option("scene", validateScene, "Scene file (JSON)")->required();

    std::string infoFile;
    auto* info = app.add_subcommand("info", "Describe a volume file (NRRD, NIfTI)");
    info->add_option("file", infoFile, "Volume file")->required();

    auto* devices = app.add_subcommand("devices", "List the Vulkan devices");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        return code == 0 ? 0 : kExitInput;
    }

    try {
        if (render->parsed()) return runRender(renderArgs);
        if (validate->parsed()) {
            cutaway::loadScene(validateScene);
            std::printf("%s: valid\n", validateScene.c_str());
            return 0;
        }
        if (info->parsed()) {
            std::fputs(cutaway::cli::describeVolume(cutaway::readVolume(infoFile), infoFile).c_str(),
                       stdout);
            return 0;
        }
        if (devices->parsed()) {
            for (const auto& d : cutaway::gpu::listDevices()) std::printf("%s\n", d.c_str());
            return 0;
        }
    } catch (const cutaway::InputError& e) {
        std::cerr << "cutaway: error: " << e.what() << "\n";
        return kExitInput;
    } catch (const std::exception& e) {
        std::cerr << "cutaway: error: " << e.what() << "\n";
        return kExitRuntime;
    }
    return kExitInput;
}

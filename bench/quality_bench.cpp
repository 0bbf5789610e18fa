// The picture-quality benchmark: each scene rendered at its default
// settings and again converged (the same scene and /render/filter, slices
// 0.125 voxels apart, every other quality setting at its best), compared as
// a display shows them (io/picture_difference.hpp). Prints a table and,
// with --json, writes the figures; asserts nothing. docs/quality.md says
// what the figures mean and which goals they are held to.
//
//   cutaway_quality [--scenes a,b,...] [--size N] [--set /pointer=value ...]
//                   [--try /pointer=value ...] [--json FILE] [--pictures DIR]
//
// --set changes both renders; --try only the default one (a lever measured
// against the same converged picture).
#include "core/error.hpp"
#include "gpu/context.hpp"
#include "io/picture_difference.hpp"
#include "io/png.hpp"
#include "job/render_job.hpp"
#include "scene/animation.hpp"
#include "scene/scene.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

using namespace cutaway;

namespace {

// The gallery's scenes and the demo (scenes/NAME.json).
const char* const kScenes[] = {"demo",
                               "fig3_axis_ct_head",
                               "fig3_surface_ct_head",
                               "fig3_segment_ct_head",
                               "fig1c_peelers_ct_head",
                               "fig7_retractor_shallow_ct_head",
                               "fig7_retractor_deep_ct_head",
                               "fig7_retractor_segment_ct_head",
                               "fig8_dilator_lens_brain",
                               "fig9_chest",
                               "fig10_frog_tools",
                               "fig12_orange_stages",
                               "turntable_peeled_head"};

// What "converged" sets on top of the scene: the finest slices the
// benchmark takes, and no early termination.
std::vector<SceneSetting> convergedSettings() {
    return {{"/render/slice_spacing", 0.125}, {"/render/termination_opacity", 1.0}};
}

// --set and --try values, read as the command line's --set is (its limits too).
std::vector<SceneSetting> parseSets(const std::vector<std::string>& sets) {
    std::vector<SceneSetting> out;
    for (const std::string& s : sets)
        out.push_back(parseSetting(s));
    return out;
}

struct Rendered {
    Image image;
    double seconds = 0.0;
};

// The scene's first frame, with its volume loaded and its bakes made.
Rendered renderTimed(const gpu::Context& ctx, const Scene& scene) {
    const auto start = std::chrono::steady_clock::now();
    Rendered r{job::renderImage(ctx, sceneAtFrame(scene, scene.animation.firstFrame)), 0.0};
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
}

// The default picture's error against the converged one, 16 times, on black:
// where the default settings fall short, and in which channels.
Image magnifiedDifference(const Image& a, const Image& b) {
    Image d(a.width, a.height);
    for (std::size_t i = 0; i < a.rgba.size(); ++i) {
        const float encodedA = linearToSrgb(std::clamp(a.rgba[i], 0.0f, 1.0f));
        const float encodedB = linearToSrgb(std::clamp(b.rgba[i], 0.0f, 1.0f));
        d.rgba[i] = i % 4 == 3 ? 1.0f : std::min(1.0f, 16.0f * std::fabs(encodedA - encodedB));
    }
    return d;
}

// name_default.png, name_converged.png and name_difference.png in `dir`.
void writePictures(const std::string& dir, const std::string& name, const Image& def,
                   const Image& conv) {
    if (dir.empty()) return;
    std::filesystem::create_directories(dir);
    writePng(dir + "/" + name + "_default.png", def);
    writePng(dir + "/" + name + "_converged.png", conv);
    Image d = magnifiedDifference(def, conv);
    for (float& v : d.rgba) // the PNG writer encodes; undo it so that 16x is linear on screen
        v = v >= 1.0f ? 1.0f : std::pow(v, 2.2f);
    writePng(dir + "/" + name + "_difference.png", d);
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"cutaway_quality: default against converged, per scene"};
    std::string scenes, jsonPath, picturesDir;
    int size = 256;
    std::vector<std::string> sets, tries;
    app.add_option("--scenes", scenes, "comma-separated scene names (default: the gallery's)");
    app.add_option("--size", size, "pixels along each side")->check(CLI::Range(16, 4096));
    app.add_option("--set", sets, "/pointer=value applied to both renders");
    app.add_option("--try", tries, "/pointer=value applied to the default render only");
    app.add_option("--json", jsonPath, "write the figures here");
    app.add_option("--pictures", picturesDir,
                   "write each scene's default, converged and 16x difference PNGs here");
    CLI11_PARSE(app, argc, argv);
    std::vector<std::string> names;
    if (scenes.empty())
        names.assign(std::begin(kScenes), std::end(kScenes));
    else
        for (std::stringstream in(scenes); std::getline(in, scenes, ',');)
            names.push_back(scenes);

    std::vector<SceneSetting> both, tried;
    try {
        both = parseSets(sets);
        tried = parseSets(tries);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "cutaway_quality: %s\n", e.what());
        return 2;
    }
    gpu::Context ctx;
    nlohmann::json records = nlohmann::json::array();
    std::printf("| scene | PSNR dB | pixels off > 4/255 | largest error | default s | "
                "converged s |\n|---|---|---|---|---|---|\n");
    for (const std::string& name : names) {
        try {
            std::vector<SceneSetting> base = both;
            base.push_back({"/render/size", {size, size}});
            std::vector<SceneSetting> fine = base;
            for (const SceneSetting& s : convergedSettings())
                fine.push_back(s);
            for (const SceneSetting& s : tried)
                base.push_back(s);
            const std::string file = "scenes/" + name + ".json";
            const Rendered def = renderTimed(ctx, loadScene(file, base));
            const Rendered conv = renderTimed(ctx, loadScene(file, fine));
            const PictureDifference d = comparePictures(def.image, conv.image);
            writePictures(picturesDir, name, def.image, conv.image);
            std::printf("| %s | %.1f | %.2f %% | %.3f | %.2f | %.2f |\n", name.c_str(), d.psnr,
                        100.0 * d.shareOff, d.maxError, def.seconds, conv.seconds);
            records.push_back({{"scene", name},
                               {"psnr", d.psnr},
                               {"share_off", d.shareOff},
                               {"max_error", d.maxError},
                               {"default_s", def.seconds},
                               {"converged_s", conv.seconds}});
        } catch (const std::exception& e) {
            std::printf("| %s | skipped: %s | | | | |\n", name.c_str(), e.what());
        }
        std::fflush(stdout);
    }
    if (!jsonPath.empty()) std::ofstream(jsonPath) << records.dump(1) << "\n";
    return 0;
}

#include "job/render_job.hpp"

#include "core/error.hpp"
#include "render/gpu_volume.hpp"
#include "render/slice_renderer.hpp"
#include "volume/phantom.hpp"

#include <cstdio>
#include <regex>

namespace cutaway::job {

Volume loadSceneVolume(const Scene& scene) {
    const VolumeSource& src = scene.volume;
    Volume volume;
    if (!src.phantom.empty())
        volume = makePhantom(src.phantom, src.phantomSize).values;
    else if (src.raw)
        volume = readRaw(src.file, *src.raw);
    else
        volume = readVolume(src.file);
    if (src.spacing) volume.spacing = *src.spacing;
    return volume;
}

bake::ValueWindow sceneWindow(const Scene& scene, const Volume& volume) {
    if (scene.volume.window) return {(*scene.volume.window)[0], (*scene.volume.window)[1]};
    const ValueRange range = valueRange(volume);
    if (range.max > range.min) return {range.min, range.max};
    return {range.min, range.min + 1.0};
}

std::string expandPattern(const std::string& pattern, int frame) {
    static const std::regex hashes("#+");
    static const std::regex printfStyle("%(0?)([0-9]*)d");
    std::smatch m;
    if (std::regex_search(pattern, m, hashes)) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%0*d", static_cast<int>(m.length(0)), frame);
        return m.prefix().str() + buf + m.suffix().str();
    }
    if (std::regex_search(pattern, m, printfStyle)) {
        const int width = m[2].length() ? std::stoi(m[2].str()) : 0;
        char buf[32];
        std::snprintf(buf, sizeof buf, m[1].length() ? "%0*d" : "%*d", width, frame);
        return m.prefix().str() + buf + m.suffix().str();
    }
    return pattern;
}

std::filesystem::path previewPath(const std::filesystem::path& exrPath) {
    std::filesystem::path p = exrPath;
    p.replace_extension(".png");
    return p;
}

void applyOverrides(Scene& scene, const RenderOverrides& overrides) {
    if (overrides.outputPattern) scene.output.pattern = *overrides.outputPattern;
    if (overrides.size) {
        scene.render.width = overrides.size->x;
        scene.render.height = overrides.size->y;
    }
    if (overrides.png) scene.output.png = true;
}

namespace {

Image renderPrepared(const gpu::Context& ctx, const Scene& scene, const Volume& volume) {
    bake::GradientBaker baker(ctx);
    render::GpuVolume gpuVolume =
        render::prepareVolume(ctx, baker, volume, sceneWindow(scene, volume));
    render::SliceRenderer renderer(ctx);
    return renderer.render(scene, gpuVolume);
}

} // namespace

Image renderImage(const gpu::Context& ctx, const Scene& scene) {
    return renderPrepared(ctx, scene, loadSceneVolume(scene));
}

} // namespace cutaway::job

#include "job/watch.hpp"

#include "core/error.hpp"
#include "io/png.hpp"
#include "job/output_paths.hpp"
#include "job/sequence.hpp"
#include "scene/animation.hpp"

#include <algorithm>
#include <chrono>

namespace cutaway::job {

FileWatch::Seen FileWatch::look(const std::filesystem::path& path) {
    Seen s;
    s.path = path;
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    s.exists = !ec && std::filesystem::exists(status);
    // A folder (DICOM) by its presence alone: the files in it are watched
    // one by one, and a preview written into it would change its time.
    if (!s.exists || !std::filesystem::is_regular_file(status)) return s;
    s.time = std::filesystem::last_write_time(path, ec);
    s.size = std::filesystem::file_size(path, ec);
    return s;
}

void FileWatch::watch(const std::vector<std::filesystem::path>& files) {
    std::vector<Seen> next;
    for (const std::filesystem::path& path : files) {
        const auto known = std::find_if(m_seen.begin(), m_seen.end(),
                                        [&](const Seen& s) { return s.path == path; });
        next.push_back(known != m_seen.end() ? *known : look(path));
    }
    m_seen = std::move(next);
}

bool FileWatch::changed() {
    bool any = false;
    for (Seen& seen : m_seen) {
        Seen now = look(seen.path);
        if (now == seen) continue;
        seen = std::move(now);
        any = true;
    }
    return any;
}

namespace {

std::vector<std::filesystem::path> pathsOf(const std::vector<RunInput>& inputs) {
    std::vector<std::filesystem::path> paths;
    for (const RunInput& input : inputs)
        paths.push_back(input.path);
    return paths;
}

} // namespace

PreviewResult PreviewRenderer::render(const PreviewRequest& request) {
    const auto start = std::chrono::steady_clock::now();
    PreviewResult result;
    result.inputs = {request.scene};
    try {
        const Scene scene = loadScene(request.scene, request.settings);
        const std::vector<RunInput> inputs = runInputs(scene);
        result.inputs = pathsOf(inputs);
        m_known = result.inputs;
        std::vector<std::filesystem::path> read; // what the renderer's caches hold
        for (const RunInput& input : inputs)
            if (input.what != "the scene") read.push_back(input.path);
        m_inputs.watch(read);
        if (m_inputs.changed() || !m_renderer) m_renderer = std::make_unique<FrameRenderer>(m_ctx);
        checkNotAnInput(request.output, inputs, "-o");
        Scene frame = sceneAtFrame(scene, scene.animation.firstFrame);
        // Draft quality unless the scene (or --set) asks for a quality.
        const nlohmann::json render = scene.document.value("render", nlohmann::json::object());
        if (!render.contains("quality") && !render.contains("refine"))
            frame.render.refine = kDraftRefine;
        if (request.size) {
            frame.render.width = request.size->x;
            frame.render.height = request.size->y;
        }
        const Image image = m_renderer->render(frame);
        result.warnings = m_renderer->takeWarnings();
        createOutputFolder(request.output);
        writePng(request.output, image);
        result.written = true;
    } catch (const Error& e) {
        result.error = e.what();
        // A scene refused for a missing file (a volume deleted, or written
        // anew) is watched with what it read last, so the file's return
        // renders again.
        for (const std::filesystem::path& path : m_known)
            if (std::find(result.inputs.begin(), result.inputs.end(), path) == result.inputs.end())
                result.inputs.push_back(path);
    }
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

std::filesystem::path defaultPreviewPath(const std::filesystem::path& scene) {
    return scene.parent_path() / (scene.stem().string() + "_preview.png");
}

} // namespace cutaway::job

#pragma once
// `cutaway watch`: a draft preview re-rendered whenever the scene or a file it
// reads changes. FileWatch tells when a file changed (its time, size or
// presence); PreviewRenderer loads the scene, renders its first frame at
// draft quality and writes the preview PNG, keeping the volume, its
// gradients and the operators' bakes across edits that leave them alone.
#include "gpu/context.hpp"
#include "job/render_job.hpp"
#include "scene/scene.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace cutaway::job {

/// The last seen state of a set of files.
class FileWatch {
public:
    /// Watches `files` from now on: files already watched keep the state last
    /// seen (a change since is still reported), new ones are looked at now.
    void watch(const std::vector<std::filesystem::path>& files);
    /// Whether any watched file changed since the last look; looks again.
    bool changed();
    std::size_t size() const { return m_seen.size(); }

private:
    struct Seen {
        std::filesystem::path path;
        bool exists = false;
        std::filesystem::file_time_type time{};
        std::uintmax_t size = 0;
        bool operator==(const Seen&) const = default;
    };
    static Seen look(const std::filesystem::path& path);
    std::vector<Seen> m_seen;
};

struct PreviewRequest {
    std::filesystem::path scene;
    std::vector<SceneSetting> settings; ///< --set
    std::filesystem::path output;       ///< the preview PNG
    std::optional<glm::ivec2> size;     ///< --size
};

struct PreviewResult {
    bool written = false;
    double seconds = 0.0;              ///< loading, rendering and writing
    std::string error;                 ///< what was wrong, when nothing was written
    std::vector<std::string> warnings; ///< what a render would warn of
    /// The files the scene reads (with itself); only the scene when it did not load.
    std::vector<std::filesystem::path> inputs;
};

class PreviewRenderer {
public:
    explicit PreviewRenderer(const gpu::Context& ctx) : m_ctx(ctx) {}
    /// Renders `request` once. Bad input and failed renders are reported in
    /// the result, not thrown: a watch goes on to the next edit.
    PreviewResult render(const PreviewRequest& request);

private:
    const gpu::Context& m_ctx;
    /// Kept across edits; made anew when a file the scene reads (other than
    /// the scene itself) changed, as its caches know files by their names.
    std::unique_ptr<FrameRenderer> m_renderer;
    FileWatch m_inputs;
    /// The files the last scene that could be read named: still watched
    /// while the scene is refused (a deleted volume comes back).
    std::vector<std::filesystem::path> m_known;
};

/// The preview's default path: SCENE's folder, its stem + "_preview.png".
std::filesystem::path defaultPreviewPath(const std::filesystem::path& scene);

} // namespace cutaway::job

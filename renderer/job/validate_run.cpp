#include "job/validate_run.hpp"

#include "core/error.hpp"
#include "job/output_paths.hpp"
#include "job/render_job.hpp"
#include "job/scene_check.hpp"
#include "scene/animation.hpp"

namespace cutaway::job {

Validation validateRun(const Scene& scene, const SequenceOptions& options,
                       const std::string& sceneName) {
    checkOutputPaths(scene, options);
    const std::vector<int> frames = framesToRender(scene, options);
    Validation v;
    v.framesInRun = static_cast<int>(frames.size());
    if (!frames.empty()) {
        v.firstFrame = frames.front();
        v.lastFrame = frames.back();
    }
    SceneFileCheck check;
    for (std::size_t i = 0; i < frames.size(); ++i) {
        // Without tracks every frame is the same scene: one check is all.
        if (i > 0 && scene.animation.tracks.empty()) break;
        ++v.checked;
        try {
            Scene frame = sceneAtFrame(scene, frames[i]);
            applyOverrides(frame, options.overrides);
            try {
                check.frame(frame);
            } catch (const InputError& e) {
                const std::string what = e.what();
                // A JSON pointer is a place in the scene file: name the file too.
                if (!what.starts_with('/')) throw;
                throw InputError(sceneName + " (frame " + std::to_string(frames[i]) + "): " + what);
            }
        } catch (const InputError& e) {
            if (++v.failed <= kFailuresShown) v.failures.push_back(e.what());
        }
    }
    v.warnings = check.takeWarnings();
    v.notes = check.takeNotes();
    return v;
}

} // namespace cutaway::job

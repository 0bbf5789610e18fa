#pragma once
// `cutaway validate`: what `render` with the same options would refuse as
// bad input, frame by frame, without a device: the scene, every frame's
// scene, the output paths and the files the frames read.
#include "job/sequence.hpp"
#include "scene/scene.hpp"

#include <string>
#include <vector>

namespace cutaway::job {

struct Validation {
    int framesInRun = 0; ///< the frames the run renders
    int firstFrame = 0;  ///< of them, when there are any
    int lastFrame = 0;
    int checked = 0;                   ///< frames checked (one when no track animates the scene)
    int failed = 0;                    ///< of them, those a render would refuse
    std::vector<std::string> failures; ///< the first few frames' errors
    std::vector<std::string> warnings; ///< what a render would warn of, each once
    std::vector<std::string> notes;    ///< what the scans give (value range, Otsu), each once
};

/// How many frames' errors Validation::failures keeps.
inline constexpr int kFailuresShown = 5;

/// Checks `scene` run with `options` (throws InputError for what fails before
/// any frame: the output paths, the frame range). `sceneName` names the
/// scene file in the frames' errors that point into it.
Validation validateRun(const Scene& scene, const SequenceOptions& options,
                       const std::string& sceneName);

} // namespace cutaway::job

#pragma once
// What `cutaway validate` checks beyond a scene's JSON, without a device: the
// files its frames name, read and checked as a render would, and the warnings
// a render would give.
#include "scene/scene.hpp"

#include <cstddef>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace cutaway::job {

/// An operator whose own box V_T misses the volume's box [lo, hi] (world mm):
/// it cuts, moves and keeps nothing. One per such operator, by its index in
/// /operators, with the warning a render prints.
struct OperatorOutside {
    std::size_t index = 0;
    std::string message;
};
std::vector<OperatorOutside> operatorsOutside(const Scene& scene, glm::dvec3 lo, glm::dvec3 hi);

/// Reads every file the frames' scenes name, each distinct one once, as
/// rendering them would: the volume (or makes the phantom), the label volume
/// (checked against the scan's grid) and the glTF models. Throws InputError
/// naming the file of the first one a render would refuse. Returns the
/// warnings a render would print, each operator once. Under sequential
/// composition the intermediate volume is not resampled: operators are
/// checked against the scan's box.
std::vector<std::string> checkSceneFiles(const std::vector<Scene>& frames);

} // namespace cutaway::job

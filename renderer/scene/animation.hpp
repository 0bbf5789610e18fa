#pragma once
// Evaluating animation tracks. The state of frame f is the scene document with
// every track's value at f written at its target pointer, then parsed and
// validated like any scene: anything numeric in a scene is animatable, and a
// track that drives a value out of range is reported like a bad scene.
#include "scene/scene.hpp"

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace cutaway {

/// The value of a track at `frame` (before the first key: the first key's
/// value; after the last: the last's). Components interpolate independently.
std::vector<double> evaluateTrack(const Track& track, double frame);

/// `document` with every track of `animation` applied at `frame`. Missing
/// objects along a target are created. Throws InputError naming the track
/// when a target cannot be written (e.g. an index past the end of an array).
nlohmann::json applyTracks(const nlohmann::json& document, const Animation& animation, int frame,
                           const std::string& source);

/// Why `pointer` cannot be written into `document`, or "" when it can: objects
/// along the way may be created, arrays may not grow nor be created, values
/// cannot be entered, and an index is plain digits ("1", not "01").
std::string pointerWriteProblem(const nlohmann::json& document, const std::string& pointer);

/// Whether JSON pointer a is b or lies inside it ("/camera/orbit" holds
/// "/camera/orbit/azimuth", not "/camera/orbital").
bool pointerWithin(const std::string& a, const std::string& b);

/// Parses "/json/pointer=VALUE"; throws InputError naming --set.
SceneSetting parseSetting(const std::string& assignment);

/// Writes each setting into `document`; throws InputError naming the setting
/// when its pointer cannot be written. A setting wins over the tracks of
/// /animation that would write the same value (a track whose target is the
/// setting's pointer, lies inside it or holds it): they are removed.
void applySettings(nlohmann::json& document, const std::vector<SceneSetting>& settings);

/// The scene of frame `frame`: tracks applied, parsed and validated. Messages
/// name the frame ("scene.json (frame 12): /camera/fov: ...").
Scene sceneAtFrame(const Scene& scene, int frame);

} // namespace cutaway

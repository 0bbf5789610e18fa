#include "scene/animation.hpp"
#include "scene/scene_sections.hpp"

#include <cmath>

namespace cutaway::scene_detail {
namespace {

// Frames as a person wrote them: 10, not 10.0.
std::string frameText(double frame) {
    if (std::abs(frame) < 1e15 && frame == std::floor(frame))
        return std::to_string(static_cast<long long>(frame));
    return describeValue(frame);
}

} // namespace

/// /animation: keyframe tracks that change the scene from frame to frame.
///
///  * frames         [integer, integer], first and last frame (inclusive), each in
///                   [0, 1000000], first <= last; default [0, 0] (a single frame)
///  * fps            number, frames per second, in (0, 1000], default 24; recorded in
///                   the EXR header, does not change what is rendered
///  * tracks         array of 0 to 1000 objects, default []:
///    * target       string, required: a JSON pointer into the scene, such as
///                   "/camera/orbit/azimuth" or "/transfer/points/2/alpha". Missing
///                   objects along it are created; the value lands where a scene
///                   author would have written it and is validated there.
///    * interpolation "linear" | "smooth" | "step", default "linear". "smooth" is a
///                   Catmull-Rom spline (C1, through every key; may overshoot).
///    * keys         array of 1 to 100000 objects, required:
///      * frame      number, in [-1000000, 1000000], strictly increasing
///      * value      number, or an array of 1 to 16 numbers (a vector); every key
///                   of a track has the same shape
void parseAnimation(JsonReader& reader, Animation& animation) {
    if (const auto frames = reader.integers("frames", 2, 2, 0, kMaxFrame)) {
        animation.firstFrame = static_cast<int>((*frames)[0]);
        animation.lastFrame = static_cast<int>((*frames)[1]);
        if (animation.firstFrame > animation.lastFrame)
            reader.error("frames", "expected the first frame <= the last, got [" +
                                       std::to_string(animation.firstFrame) + ", " +
                                       std::to_string(animation.lastFrame) + "]");
    }
    animation.fps = reader.number("fps", animation.fps, Range::openClosed(0.0, 1000.0));

    reader.objects("tracks", 0, 1000, [&](JsonReader& t, std::size_t index) {
        Track track;
        if (auto target = t.string("target", {}, true)) {
            track.target = *target;
            // Two tracks of one value: the later would silently win.
            for (std::size_t j = 0; j < index && j < animation.tracks.size(); ++j) {
                const std::string& other = animation.tracks[j].target;
                if (other.empty() ||
                    !(pointerWithin(*target, other) || pointerWithin(other, *target)))
                    continue;
                t.error("target", describeValue(*target) + " writes what track " +
                                      std::to_string(j) + " (" + describeValue(other) +
                                      ") writes; give each value one track");
                break;
            }
            try {
                nlohmann::json::json_pointer pointer(track.target);
                if (pointer.empty() || track.target.rfind("/animation", 0) == 0 ||
                    track.target == "/version")
                    t.error("target", "expected a pointer to a value of the scene outside "
                                      "/animation and /version, got " +
                                          describeValue(track.target));
            } catch (const nlohmann::json::exception&) {
                t.error("target", "expected a JSON pointer such as \"/camera/orbit/azimuth\", "
                                  "got " +
                                      describeValue(track.target));
            }
        }
        const std::string interpolation =
            t.string("interpolation", "linear", {"linear", "smooth", "step"});
        track.interpolation = interpolation == "smooth" ? Interpolation::Smooth
                              : interpolation == "step" ? Interpolation::Step
                                                        : Interpolation::Linear;
        t.objects(
            "keys", 1, 100000,
            [&](JsonReader& k, std::size_t keyIndex) {
                Keyframe key;
                key.frame = k.number("frame", Range::closed(-1e6, 1e6), true).value_or(NAN);
                if (const nlohmann::json* value = k.find("value")) {
                    const std::string pointer = k.pointerOf("value");
                    if (value->is_array()) {
                        key.isArray = true;
                        key.value = k.asNumbers(*value, pointer, 1, 16,
                                                Range::closed(-kMaxValue, kMaxValue))
                                        .value_or(std::vector<double>{});
                    } else if (auto v = k.asNumber(*value, pointer,
                                                   Range::closed(-kMaxValue, kMaxValue))) {
                        key.value = {*v};
                    }
                } else {
                    k.error("value", "missing; expected a number or an array of numbers");
                }
                if (!track.keys.empty() && !std::isnan(key.frame)) {
                    const Keyframe& prev = track.keys.back();
                    if (!(key.frame > prev.frame))
                        k.error("frame", "expected a frame greater than the previous key's (" +
                                             frameText(prev.frame) + "), got " +
                                             frameText(key.frame));
                    if (!key.value.empty() && !prev.value.empty() &&
                        (key.value.size() != prev.value.size() || key.isArray != prev.isArray))
                        k.error("value", "expected the same shape as key " +
                                             std::to_string(keyIndex - 1) + "'s value");
                }
                track.keys.push_back(key);
            },
            true);
        animation.tracks.push_back(std::move(track));
    });
}

} // namespace cutaway::scene_detail

// The /camera and /lights sections of a scene document.
#include "scene/scene_sections.hpp"

#include <cmath>
#include <string>

namespace cutaway::scene_detail {

namespace {

const Range kCoordinate = Range::closed(-kMaxCoordinate, kMaxCoordinate);

std::string formatVector(const glm::dvec3& v) {
    std::string text(1, '[');
    for (int i = 0; i < 3; ++i) {
        if (i > 0) text += ", ";
        text += formatNumber(v[i]);
    }
    text += ']';
    return text;
}

/// /camera/orbit: the eye circles `target`.
///
///  * azimuth    number, degrees, in [-36000, 36000], default 0
///               Rotation about `up`; 0 puts the eye on the -y side looking
///               along +y, 90 on the +x side.
///  * elevation  number, degrees, in (-90, 90), default 0
///               Angle of the eye above the plane perpendicular to `up`.
///  * distance   number, mm, in [0, 1e6], default 0
///               From the target to the eye; 0 fits the volume's bounding
///               sphere in view.
///  * target     [number x3], mm, world space, each in [-1e6, 1e6], default [0, 0, 0]
///               (the volume's centre)
///  * up         [number x3], world space, non-zero, default [0, 0, 1]
///  * space      "volume" | "lps" | "ras", default "volume": the frame of
///               `target` and `up` (scene.hpp, CoordinateSpace)
void parseOrbit(JsonReader& reader, Camera& camera) {
    camera.useOrbit = true;
    camera.space = readSpace(reader);
    camera.azimuthDeg = reader.number("azimuth", camera.azimuthDeg, -36000.0, 36000.0);
    camera.elevationDeg = reader.number("elevation", camera.elevationDeg, Range::open(-90.0, 90.0));
    camera.distance = reader.number("distance", camera.distance, 0.0, kMaxCoordinate);
    camera.target = reader.vec3("target", camera.target, kCoordinate);
    camera.targetGiven = reader.has("target");
    camera.up = readDirection(reader, "up", false).value_or(camera.up);
}

/// /camera/look_at: the eye at a point, looking at another.
///
///  * eye     [number x3], mm, world space, each in [-1e6, 1e6], required;
///            different from `target`
///  * target  [number x3], mm, world space, each in [-1e6, 1e6], default [0, 0, 0]
///  * up      [number x3], world space, non-zero and not parallel to
///            target - eye, default [0, 0, 1]
///  * space   "volume" | "lps" | "ras", default "volume": the frame of the three
void parseLookAt(JsonReader& reader, Camera& camera) {
    camera.useOrbit = false;
    camera.space = readSpace(reader);
    const auto eye = reader.vec3("eye", kCoordinate, true);
    const auto target = reader.vec3("target", kCoordinate);
    const auto up = readDirection(reader, "up", false);
    camera.eye = eye.value_or(camera.eye);
    camera.target = target.value_or(camera.target);
    camera.targetGiven = target.has_value();
    camera.up = up.value_or(camera.up);
    if (!eye || (reader.has("target") && !target) || (reader.has("up") && !up)) return;

    const glm::dvec3 view = camera.target - camera.eye;
    if (glm::length(view) <= 1.0e-9 * (1.0 + glm::length(camera.eye))) {
        reader.expected(reader.pointerOf("eye"),
                        "a point different from target " + formatVector(camera.target),
                        *reader.find("eye"));
        return;
    }
    const double sine = glm::length(glm::cross(glm::normalize(view), glm::normalize(camera.up)));
    if (sine < 1.0e-6) {
        const nlohmann::json* given = reader.find("up");
        reader.expected(reader.pointerOf("up"),
                        "a direction not parallel to the view direction (target - eye = " +
                            formatVector(view) + ")",
                        given != nullptr ? *given : nlohmann::json::array({0, 0, 1}));
    }
}

} // namespace

CoordinateSpace readSpace(JsonReader& reader) {
    const std::string space = reader.string("space", "volume", {"volume", "lps", "ras"});
    return space == "lps"   ? CoordinateSpace::LPS
           : space == "ras" ? CoordinateSpace::RAS
                            : CoordinateSpace::Volume;
}

std::optional<glm::dvec3> readDirection(JsonReader& reader, std::string_view key, bool required) {
    const auto direction = reader.vec3(key, kCoordinate, required);
    if (!direction) return std::nullopt;
    if (glm::length(*direction) <= 1.0e-9) {
        reader.expected(reader.pointerOf(key), "a non-zero direction", *reader.find(key));
        return std::nullopt;
    }
    return direction;
}

/// /camera/margin and /camera/zoom, which act on a fitted view only: an orbit
/// whose distance (perspective) or ortho_height (orthographic) is left to fit.
void parseFraming(JsonReader& reader, Camera& camera) {
    if (reader.has("margin"))
        camera.margin = reader.number("margin", 0.0, Range::closed(0.0, 0.45));
    camera.zoom = reader.number("zoom", camera.zoom, Range::closed(0.01, 100.0));
    const bool fitted = camera.useOrbit &&
                        (camera.projection == Projection::Orthographic ? camera.orthoHeight <= 0.0
                                                                       : camera.distance <= 0.0);
    for (const char* key : {"margin", "zoom"})
        if (reader.has(key) && !fitted)
            reader.diagnostics().error(reader.pointerOf(key),
                                       "acts on a fitted view: an orbit without a distance "
                                       "(perspective) or ortho_height (orthographic)");
}

/// /camera: how the volume is viewed. At most one of `orbit` or `look_at`;
/// without either, an orbit with its defaults.
///
///  * projection    string, "perspective" or "orthographic", default "perspective"
///  * fov           number, degrees, in (0, 170), default 30
///                  Vertical field of view of the perspective projection.
///  * ortho_height  number, mm, in [0, 1e6], default 0
///                  Height of the orthographic view; 0 fits the volume's
///                  bounding sphere.
///  * fit           "volume" | "deformed" | "sequence", default "volume": what a
///                  distance (or ortho_height) of 0 fits in view: the volume's
///                  box; with what the frame's operators move; with what they
///                  move over the whole animation (the view stays still)
///  * margin        number in [0, 0.45], default none: a fitted view frames the
///                  box itself, this fraction of the frame kept free on each side
///  * zoom          number in [0.01, 100], default 1: a factor on a fitted view
///  * orbit         object, default {}: see parseOrbit above
///  * look_at       object, default none: see parseLookAt above
void parseCamera(JsonReader& reader, Camera& camera) {
    const std::string projection =
        reader.string("projection", "perspective", {"perspective", "orthographic"});
    camera.projection =
        projection == "orthographic" ? Projection::Orthographic : Projection::Perspective;
    camera.fovDeg = reader.number("fov", camera.fovDeg, Range::open(0.0, 170.0));
    camera.orthoHeight = reader.number("ortho_height", camera.orthoHeight, 0.0, kMaxCoordinate);
    const std::string fit = reader.string("fit", "volume", {"volume", "deformed", "sequence"});
    camera.fit = fit == "deformed"   ? CameraFit::Deformed
                 : fit == "sequence" ? CameraFit::Sequence
                                     : CameraFit::Volume;

    if (reader.has("orbit") && reader.has("look_at")) {
        reader.errorHere("expected at most one of \"orbit\" or \"look_at\", got both");
    }
    reader.object("orbit", [&](JsonReader& orbit) { parseOrbit(orbit, camera); });
    reader.object("look_at", [&](JsonReader& lookAt) { parseLookAt(lookAt, camera); });
    parseFraming(reader, camera);
}

/// /lights: the lighting of shaded samples (see /render/shading).
///
///  * ambient      number, in [0, 1], default 0.2
///                 Light that reaches every sample, whatever its gradient.
///  * headlight    number, in [0, 10], default 0.8
///                 Intensity of a white directional light shining from the eye.
///  * directional  array of at most 4 objects, default []
///    * direction  [number x3], world space, non-zero, required
///                 The direction the light travels (from the light to the scene).
///    * color      [number x3], linear RGB, each in [0, 1], default [1, 1, 1]
///    * intensity  number, in [0, 10], default 1
void parseLights(JsonReader& reader, Lights& lights) {
    lights.ambient = float(reader.number("ambient", lights.ambient, 0.0, 1.0));
    lights.headlight = float(reader.number("headlight", lights.headlight, 0.0, 10.0));
    lights.directional.clear();
    reader.objects("directional", 0, 4, [&](JsonReader& light, std::size_t) {
        DirectionalLight result;
        result.direction = readDirection(light, "direction", true).value_or(result.direction);
        result.color = light.colour("color", result.color);
        result.intensity = float(light.number("intensity", result.intensity, 0.0, 10.0));
        lights.directional.push_back(result);
    });
}

} // namespace cutaway::scene_detail

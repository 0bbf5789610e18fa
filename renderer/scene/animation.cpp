#include "scene/animation.hpp"

#include "core/error.hpp"
#include "io/json_limits.hpp"
#include "scene/json_reader.hpp"

#include <algorithm>

namespace cutaway {
namespace {

// Hermite basis on [0, 1].
double hermite(double p0, double m0, double p1, double m1, double t) {
    const double t2 = t * t, t3 = t2 * t;
    return (2 * t3 - 3 * t2 + 1) * p0 + (t3 - 2 * t2 + t) * m0 + (-2 * t3 + 3 * t2) * p1 +
           (t3 - t2) * m1;
}

// Catmull-Rom tangent at key k in value per frame, aware of uneven key
// spacing; one-sided at the ends.
double tangent(const std::vector<Keyframe>& keys, std::size_t k, std::size_t c) {
    const std::size_t lo = k == 0 ? 0 : k - 1;
    const std::size_t hi = std::min(k + 1, keys.size() - 1);
    if (lo == hi) return 0.0;
    return (keys[hi].value[c] - keys[lo].value[c]) / (keys[hi].frame - keys[lo].frame);
}

} // namespace

// Refuses what nlohmann would do: pad a too-short array with nulls, throw on an
// index it cannot read ("01", 20 digits), and below a missing key create an
// array for an index token (padded with nulls up to it) or throw for "".
std::string pointerWriteProblem(const nlohmann::json& document, const std::string& target) {
    // Built piecewise: GCC 12 warns (-Wrestrict, falsely) on "x" + substr.
    const auto atPrefix = [&](std::size_t length, const char* problem) {
        std::string message = "\"";
        message += abbreviatePointer(target.substr(0, length));
        message += problem;
        return message;
    };
    const nlohmann::json* node = &document;
    std::size_t start = 1;
    while (start <= target.size()) {
        const std::size_t end = std::min(target.find('/', start), target.size());
        const std::string token = target.substr(start, end - start);
        const bool digits = token.find_first_not_of("0123456789") == std::string::npos;
        if (!node) {
            // nlohmann makes an array of a missing value for "-" and for digits, "" included.
            if (digits || token == "-")
                return atPrefix(start - 1,
                                "\" does not exist; only objects are created on the way");
        } else if (node->is_array()) {
            if (!digits || token.empty() || token.size() > 9 ||
                (token.size() > 1 && token[0] == '0') || std::stoul(token) >= node->size())
                return "\"" + abbreviate(token) + "\" is not an index of an array of " +
                       std::to_string(node->size());
            node = &(*node)[std::stoul(token)];
        } else if (node->is_object()) {
            auto it = node->find(nlohmann::json::json_pointer("/" + token).back());
            node = it == node->end() ? nullptr : &*it;
        } else {
            return atPrefix(start - 1, "\" holds a value, not an object");
        }
        start = end + 1;
    }
    return {};
}

std::vector<double> evaluateTrack(const Track& track, double frame) {
    const auto& keys = track.keys;
    if (keys.empty()) return {};
    if (frame <= keys.front().frame) return keys.front().value;
    if (frame >= keys.back().frame) return keys.back().value;
    const auto next = std::upper_bound(keys.begin(), keys.end(), frame,
                                       [](double f, const Keyframe& k) { return f < k.frame; });
    const std::size_t k1 = static_cast<std::size_t>(next - keys.begin()), k0 = k1 - 1;
    const Keyframe& a = keys[k0];
    const Keyframe& b = keys[k1];
    if (track.interpolation == Interpolation::Step) return a.value;
    const double span = b.frame - a.frame;
    const double t = (frame - a.frame) / span;
    std::vector<double> out(a.value.size());
    for (std::size_t c = 0; c < out.size(); ++c) {
        if (track.interpolation == Interpolation::Linear)
            out[c] = a.value[c] + (b.value[c] - a.value[c]) * t;
        else // tangents are per frame; the basis runs over the span in [0, 1]
            out[c] = hermite(a.value[c], tangent(keys, k0, c) * span, b.value[c],
                             tangent(keys, k1, c) * span, t);
    }
    return out;
}

nlohmann::json applyTracks(const nlohmann::json& document, const Animation& animation, int frame,
                           const std::string& source) {
    nlohmann::json out = document;
    for (std::size_t i = 0; i < animation.tracks.size(); ++i) {
        const Track& track = animation.tracks[i];
        const std::vector<double> v = evaluateTrack(track, frame);
        const bool isArray = !track.keys.empty() && track.keys.front().isArray;
        nlohmann::json value = isArray ? nlohmann::json(v) : nlohmann::json(v.empty() ? 0.0 : v[0]);
        const std::string problem = pointerWriteProblem(out, track.target);
        if (!problem.empty())
            throw InputError(source + ": /animation/tracks/" + std::to_string(i) +
                             "/target: cannot write " + abbreviatePointer(track.target) + ": " +
                             problem);
        out[nlohmann::json::json_pointer(track.target)] = value;
    }
    return out;
}

SceneSetting parseSetting(const std::string& assignment) {
    const std::size_t eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0 || assignment[0] != '/')
        throw InputError("--set " + abbreviate(assignment) +
                         ": expected /json/pointer=VALUE, e.g. /camera/orbit/azimuth=90");
    SceneSetting setting;
    setting.pointer = assignment.substr(0, eq);
    const std::string name = "--set " + abbreviatePointer(setting.pointer);
    try {
        (void)nlohmann::json::json_pointer(setting.pointer);
    } catch (const nlohmann::json::exception&) {
        throw InputError(name + ": " + describeValue(setting.pointer) + " is not a JSON pointer");
    }
    // The bounds of a scene file's text (io/json_limits.hpp) hold here too.
    const std::string text = assignment.substr(eq + 1);
    if (text.size() > kMaxSceneStringBytes)
        throw InputError(name + ": a value of " + std::to_string(text.size() >> 10) +
                         " KiB, more than the " + std::to_string(kMaxSceneStringBytes >> 10) +
                         " KiB a scene's value may be");
    checkJsonText(text, name, kSceneJsonLimits);
    setting.value = nlohmann::json::parse(text, nullptr, false);
    if (setting.value.is_discarded()) setting.value = text;
    return setting;
}

namespace {

// A setting wins over the tracks that would write the same value: those
// whose target is the setting's pointer, lies inside it or holds it.
void dropTracksOverriddenBy(nlohmann::json& document, const std::string& pointer) {
    if (pointerWithin(pointer, "/animation") || !document.is_object()) return;
    const auto animation = document.find("animation");
    if (animation == document.end() || !animation->is_object()) return;
    const auto tracks = animation->find("tracks");
    if (tracks == animation->end() || !tracks->is_array()) return;
    nlohmann::json kept = nlohmann::json::array();
    for (const nlohmann::json& track : *tracks) {
        const auto target = track.is_object() ? track.find("target") : track.end();
        const bool overridden = target != track.end() && target->is_string() &&
                                (pointerWithin(target->get<std::string>(), pointer) ||
                                 pointerWithin(pointer, target->get<std::string>()));
        if (!overridden) kept.push_back(track);
    }
    *tracks = std::move(kept);
}

} // namespace

bool pointerWithin(const std::string& a, const std::string& b) {
    return a == b || (a.size() > b.size() && a.starts_with(b) && a[b.size()] == '/');
}

void applySettings(nlohmann::json& document, const std::vector<SceneSetting>& settings) {
    for (const SceneSetting& s : settings) {
        const std::string problem = pointerWriteProblem(document, s.pointer);
        if (!problem.empty())
            throw InputError("--set " + abbreviatePointer(s.pointer) +
                             ": cannot write there: " + problem);
        document[nlohmann::json::json_pointer(s.pointer)] = s.value;
        dropTracksOverriddenBy(document, s.pointer);
    }
}

namespace {

// Each line of a frame's parse error that names a value a track wrote gets the
// track's name, and for a whole number written by an interpolating track the
// remedy: the track is where the user has to look, not the value's pointer.
std::string namingTracks(const std::string& message, const std::string& source,
                         const Animation& animation) {
    std::string out;
    std::size_t start = 0;
    while (start < message.size()) {
        const std::size_t end = std::min(message.find('\n', start), message.size());
        std::string line = message.substr(start, end - start);
        const std::string prefix = source + ": /";
        if (line.starts_with(prefix)) {
            const std::size_t colon = line.find(": ", prefix.size());
            const std::string pointer = line.substr(prefix.size() - 1, colon - prefix.size() + 1);
            // Tracks apply in order, so the last one that wrote the value counts.
            for (std::size_t i = animation.tracks.size(); i-- > 0;) {
                const Track& track = animation.tracks[i];
                if (!pointerWithin(pointer, track.target)) continue;
                line += " (written by /animation/tracks/" + std::to_string(i) + ")";
                if (line.find("expected an integer") != std::string::npos &&
                    track.interpolation != Interpolation::Step)
                    line += "; a whole number between keys needs \"interpolation\": \"step\"";
                break;
            }
        }
        out += line;
        if (end < message.size()) out += '\n';
        start = end + 1;
    }
    return out;
}

} // namespace

Scene sceneAtFrame(const Scene& scene, int frame) {
    if (scene.animation.tracks.empty()) {
        Scene s = scene;
        s.frame = frame;
        return s;
    }
    const std::string source =
        (scene.file.empty() ? std::string("<string>") : scene.file.string()) + " (frame " +
        std::to_string(frame) + ")";
    const nlohmann::json document = applyTracks(scene.document, scene.animation, frame, source);
    try {
        Scene s = parseScene(document, scene.baseDir, source);
        s.file = scene.file;
        s.frame = frame;
        return s;
    } catch (const InputError& e) {
        throw InputError(namingTracks(e.what(), source, scene.animation));
    }
}

} // namespace cutaway

#include "scene/label_table.hpp"

#include "core/error.hpp"
#include "core/quote_text.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace cutaway {
namespace {

constexpr std::uintmax_t kMaxTableBytes = 16u << 20;

float srgbToLinear(int byte) {
    const double c = byte / 255.0;
    return float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

bool integer(const std::string& word, std::int64_t lo, std::int64_t hi, std::int64_t& out) {
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(word.c_str(), &end, 10);
    if (word.empty() || *end != '\0' || errno != 0 || v < lo || v > hi) return false;
    out = v;
    return true;
}

struct Line {
    std::int64_t id = 0;
    std::string name;
    std::optional<glm::ivec3> rgb;
    bool colorOutOfRange = false; // three whole numbers, not all in [0, 255]
};

// `id r g b a visible mesh "name"` (ITK-SNAP).
std::optional<Line> quotedLine(const std::string& text) {
    const std::size_t open = text.find('"'), close = text.rfind('"');
    if (close == open) return std::nullopt;
    std::istringstream words(text.substr(0, open));
    std::vector<std::string> w;
    for (std::string s; words >> s;)
        w.push_back(s);
    Line l;
    std::int64_t c[3] = {};
    if (w.size() < 4 || !integer(w[0], 0, 2147483647, l.id)) return std::nullopt;
    for (int i = 0; i < 3; ++i)
        if (!integer(w[1 + i], 0, 255, c[i])) return std::nullopt;
    l.rgb = glm::ivec3(int(c[0]), int(c[1]), int(c[2]));
    l.name = text.substr(open + 1, close - open - 1);
    return l;
}

// `id name [r g b [a]]` (FreeSurfer, 3D Slicer, plain lists).
std::optional<Line> plainLine(const std::string& text) {
    std::istringstream words(text);
    std::vector<std::string> w;
    for (std::string s; words >> s;)
        w.push_back(s);
    Line l;
    if (w.size() < 2 || !integer(w[0], 0, 2147483647, l.id)) return std::nullopt;
    l.name = w[1];
    std::int64_t c[3] = {};
    constexpr std::int64_t kAny = std::int64_t{1} << 40;
    if (w.size() >= 5 && integer(w[2], -kAny, kAny, c[0]) && integer(w[3], -kAny, kAny, c[1]) &&
        integer(w[4], -kAny, kAny, c[2])) {
        l.colorOutOfRange = std::any_of(c, c + 3, [](std::int64_t v) { return v < 0 || v > 255; });
        l.rgb = glm::ivec3(int(c[0] & 0xff), int(c[1] & 0xff), int(c[2] & 0xff));
    }
    return l;
}

// Kelly's colours as sRGB bytes, in his order (white and black left out).
constexpr unsigned kKelly[kPaletteColours] = {0xF3C300, 0x875692, 0xF38400, 0xA1CAF1, 0xBE0032,
                                              0xC2B280, 0x848482, 0x008856, 0xE68FAC, 0x0067A5,
                                              0xF99379, 0x604E97, 0xF6A600, 0xB3446C, 0xDCD300,
                                              0x882D17, 0x8DB600, 0x654522, 0xE25822, 0x2B3D26};

} // namespace

glm::vec3 paletteColour(std::size_t index) {
    const unsigned c = kKelly[index % kPaletteColours];
    return {srgbToLinear(int(c >> 16)), srgbToLinear(int((c >> 8) & 0xff)),
            srgbToLinear(int(c & 0xff))};
}

LabelTable readLabelTable(const std::filesystem::path& path) {
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) throw InputError(path.string() + ": cannot read the label table");
    if (size > kMaxTableBytes)
        throw InputError(path.string() + ": a label table of " + std::to_string(size) +
                         " bytes; at most 16 MiB");
    std::ifstream in(path);
    LabelTable table;
    std::map<std::int64_t, int> idLines;
    std::map<std::string, int> nameLines;
    std::string text;
    for (int number = 1; std::getline(in, text); ++number) {
        if (const std::size_t first = text.find_first_not_of(" \t");
            first != std::string::npos && text[first] == '#')
            continue;
        if (const std::size_t hash = text.find('#');
            hash != std::string::npos && text.find('"') == std::string::npos)
            text.erase(hash);
        if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
        const std::optional<Line> line =
            text.find('"') != std::string::npos ? quotedLine(text) : plainLine(text);
        if (!line || line->name.empty())
            throw InputError(path.string() + ":" + std::to_string(number) +
                             ": not a label line (expected \"id name [r g b [a]]\" or ITK-SNAP's "
                             "\"id r g b a visible mesh \\\"name\\\"\")");
        const std::string at = path.string() + ":" + std::to_string(number) + ": ";
        if (line->colorOutOfRange)
            throw InputError(at + "a colour outside [0, 255] for label " +
                             std::to_string(line->id));
        if (const auto [seen, fresh] = idLines.emplace(line->id, number); !fresh)
            throw InputError(at + "label " + std::to_string(line->id) + " again (first on line " +
                             std::to_string(seen->second) + "); each id is named once");
        if (const auto [seen, fresh] = nameLines.emplace(line->name, number); !fresh)
            throw InputError(at + "the name " + quoteText(line->name) + " again (first on line " +
                             std::to_string(seen->second) + "); each name is one label's");
        table.names.emplace(line->name, line->id);
        if (line->rgb)
            table.colors[line->id] = glm::vec3(
                srgbToLinear(line->rgb->x), srgbToLinear(line->rgb->y), srgbToLinear(line->rgb->z));
    }
    if (table.names.empty()) throw InputError(path.string() + ": the label table names no label");
    return table;
}

} // namespace cutaway

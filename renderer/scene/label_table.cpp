#include "scene/label_table.hpp"

#include "core/error.hpp"

#include <cmath>
#include <fstream>
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
    if (w.size() >= 5 && integer(w[2], 0, 255, c[0]) && integer(w[3], 0, 255, c[1]) &&
        integer(w[4], 0, 255, c[2]))
        l.rgb = glm::ivec3(int(c[0]), int(c[1]), int(c[2]));
    return l;
}

} // namespace

LabelTable readLabelTable(const std::filesystem::path& path) {
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) throw InputError(path.string() + ": cannot read the label table");
    if (size > kMaxTableBytes)
        throw InputError(path.string() + ": a label table of " + std::to_string(size) +
                         " bytes; at most 16 MiB");
    std::ifstream in(path);
    LabelTable table;
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
        table.names.emplace(line->name, line->id);
        if (line->rgb)
            table.colors[line->id] = glm::vec3(
                srgbToLinear(line->rgb->x), srgbToLinear(line->rgb->y), srgbToLinear(line->rgb->z));
    }
    if (table.names.empty()) throw InputError(path.string() + ": the label table names no label");
    return table;
}

} // namespace cutaway

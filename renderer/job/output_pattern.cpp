#include "job/output_pattern.hpp"

#include <algorithm>
#include <vector>

namespace cutaway::job {

namespace {

// A frame number's place in a pattern: a run of '#', or "%d", "%Nd", "%0Nd".
struct Placeholder {
    std::size_t position = 0, length = 0; ///< of the placeholder's text
    std::size_t width = 0;                ///< digits the number is padded to
    char fill = '0';
};

// Wider than any file name may be; keeps a width such as "%99999999999d"
// from overflowing. checkOutputPaths refuses the name it makes.
constexpr std::size_t kMaxWidth = 4096;

// A '%' that starts a placeholder, or "%%", which stands for '%' as in printf.
struct PatternScan {
    std::vector<Placeholder> placeholders;
    std::vector<std::size_t> percents; ///< where each "%%" starts
};

PatternScan scan(const std::string& p) {
    PatternScan out;
    std::size_t i = 0;
    while (i < p.size()) {
        if (p[i] == '#') {
            const std::size_t end = std::min(p.find_first_not_of('#', i), p.size());
            out.placeholders.push_back({i, end - i, end - i, '0'});
            i = end;
            continue;
        }
        if (p[i] == '%' && i + 1 < p.size() && p[i + 1] == '%') {
            out.percents.push_back(i);
            i += 2;
            continue;
        }
        if (p[i] == '%') {
            std::size_t j = i + 1, width = 0;
            const char fill = j < p.size() && p[j] == '0' ? '0' : ' ';
            if (fill == '0') ++j;
            for (; j < p.size() && p[j] >= '0' && p[j] <= '9'; ++j)
                width = std::min(width * 10 + std::size_t(p[j] - '0'), kMaxWidth);
            if (j < p.size() && p[j] == 'd') {
                out.placeholders.push_back({i, j + 1 - i, width, fill});
                i = j + 1;
                continue;
            }
        }
        ++i;
    }
    return out;
}

// `frame` in decimal, padded to `width` with zeros or spaces.
std::string padded(int frame, std::size_t width, char fill) {
    std::string digits = std::to_string(frame);
    if (digits.size() < width) digits.insert(0, width - digits.size(), fill);
    return digits;
}

} // namespace

std::string expandPattern(const std::string& pattern, int frame) {
    const PatternScan found = scan(pattern);
    std::string out;
    std::size_t from = 0, h = 0, q = 0;
    // Placeholders and "%%" do not overlap; take them in the order they come.
    while (h < found.placeholders.size() || q < found.percents.size()) {
        const bool hole =
            q == found.percents.size() ||
            (h < found.placeholders.size() && found.placeholders[h].position < found.percents[q]);
        const std::size_t at = hole ? found.placeholders[h].position : found.percents[q];
        out += pattern.substr(from, at - from);
        if (hole) {
            const Placeholder& ph = found.placeholders[h++];
            out += padded(frame, ph.width, ph.fill);
            from = at + ph.length;
        } else {
            out += '%';
            from = at + 2;
            ++q;
        }
    }
    return out + pattern.substr(from);
}

int framePlaceholders(const std::string& pattern) {
    return static_cast<int>(scan(pattern).placeholders.size());
}

std::filesystem::path previewPath(const std::filesystem::path& exrPath) {
    std::filesystem::path p = exrPath;
    p.replace_extension(".png");
    return p;
}

} // namespace cutaway::job

// The text side of json_reader.hpp: diagnostics, value formatting, typo
// suggestions, and parsing JSON text with positioned syntax errors.
#include "core/error.hpp"
#include "io/json_limits.hpp"
#include "scene/json_reader.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace cutaway {

void Diagnostics::error(std::string_view pointer, std::string_view message) {
    std::string line = m_source;
    line += ": ";
    line += pointer.empty() ? std::string("(root)") : abbreviatePointer(pointer);
    line += ": ";
    line += message;
    m_messages.push_back(std::move(line));
}

void Diagnostics::throwIfAny() const {
    if (m_messages.empty()) return;
    std::string text;
    for (const std::string& message : m_messages) {
        if (!text.empty()) text += '\n';
        text += message;
    }
    throw InputError(text);
}

bool Range::contains(double value) const {
    if (!std::isfinite(value)) return false;
    if (minOpen ? !(value > min) : !(value >= min)) return false;
    if (maxOpen ? !(value < max) : !(value <= max)) return false;
    return true;
}

std::string Range::describe() const {
    const bool hasMin = std::isfinite(min);
    const bool hasMax = std::isfinite(max);
    if (hasMin && hasMax) {
        return std::string(" in ") + (minOpen ? "(" : "[") + formatNumber(min) + ", " +
               formatNumber(max) + (maxOpen ? ")" : "]");
    }
    if (hasMin) return (minOpen ? " > " : " >= ") + formatNumber(min);
    if (hasMax) return (maxOpen ? " < " : " <= ") + formatNumber(max);
    return "";
}

std::string formatNumber(double value) {
    if (std::isnan(value)) return "nan";
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    std::array<char, 64> buffer{};
    // A value that needs more than 15 significant digits is arithmetic's
    // (an animation's interpolation, a unit conversion), not the user's text:
    // 1.3738400000000002 is shown as 1.37384.
    const auto rounded = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value,
                                       std::chars_format::general, 15);
    double back = 0.0;
    std::from_chars(buffer.data(), rounded.ptr, back);
    if (back != value) return std::string(buffer.data(), rounded.ptr);
    // Plain digits for everyday magnitudes ("1000000", not "1e+06"); exponents otherwise.
    const double magnitude = std::abs(value);
    const bool plain = magnitude == 0.0 || (magnitude >= 1.0e-4 && magnitude < 1.0e15);
    const auto result = plain ? std::to_chars(buffer.data(), buffer.data() + buffer.size(), value,
                                              std::chars_format::fixed)
                              : std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
    return std::string(buffer.data(), result.ptr);
}

namespace {

// Appends `value` as compact JSON (as dump() writes it) to `out`, stopping
// soon after `out` passes `limit` bytes, so that a 10 MB string or 60,000
// arrays inside each other cost no more than a short value. The recursion
// is as deep as `limit` at most: every level appends a bracket first.
void appendJson(const nlohmann::json& value, std::string& out, std::size_t limit) {
    constexpr auto kReplace = nlohmann::json::error_handler_t::replace;
    if (out.size() > limit) return;
    if (value.is_string()) {
        // Enough of the string to pass the limit; dump() escapes it.
        const std::string& text = value.get_ref<const std::string&>();
        const std::size_t room = limit - out.size() + 8;
        out += nlohmann::json(text.substr(0, room)).dump(-1, ' ', false, kReplace);
        return;
    }
    if (!value.is_structured()) {
        out += value.dump(-1, ' ', false, kReplace);
        return;
    }
    const bool array = value.is_array();
    out += array ? '[' : '{';
    bool first = true;
    for (auto it = value.begin(); it != value.end() && out.size() <= limit; ++it) {
        if (!first) out += ',';
        first = false;
        if (!array) {
            appendJson(nlohmann::json(it.key().substr(0, limit)), out, limit);
            out += ':';
        }
        appendJson(*it, out, limit);
    }
    out += array ? ']' : '}';
}

} // namespace

std::string abbreviate(std::string_view text, std::size_t maxChars) {
    if (text.size() <= maxChars || maxChars <= 3) return std::string(text);
    std::string cut(text.substr(0, maxChars - 3));
    // Do not cut a UTF-8 sequence in half.
    while (!cut.empty() && (static_cast<unsigned char>(cut.back()) & 0xC0) == 0x80)
        cut.pop_back();
    if (!cut.empty() && (static_cast<unsigned char>(cut.back()) & 0x80) != 0) cut.pop_back();
    return cut + "...";
}

std::string abbreviatePointer(std::string_view pointer) {
    constexpr std::size_t kLongestToken = 40;
    std::string shown;
    std::size_t start = 0;
    while (start < pointer.size()) {
        std::size_t end = pointer.find('/', start + 1);
        if (end == std::string_view::npos) end = pointer.size();
        shown += abbreviate(pointer.substr(start, end - start), kLongestToken);
        start = end;
    }
    return abbreviate(shown, 5 * kLongestToken); // a pointer of many tokens
}

std::string describeValue(const nlohmann::json& value, std::size_t maxChars) {
    if (value.is_number_float()) return abbreviate(formatNumber(value.get<double>()), maxChars);
    std::string text;
    appendJson(value, text, maxChars);
    return abbreviate(text, maxChars);
}

std::size_t editDistance(std::string_view a, std::string_view b) {
    // d[i][j]: the distance between the first i characters of a and the first j of b.
    const std::size_t columns = b.size() + 1;
    std::vector<std::size_t> d((a.size() + 1) * columns);
    const auto at = [&](std::size_t i, std::size_t j) -> std::size_t& {
        return d[i * columns + j];
    };
    for (std::size_t i = 0; i <= a.size(); ++i)
        at(i, 0) = i;
    for (std::size_t j = 0; j <= b.size(); ++j)
        at(0, j) = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t substitution = at(i - 1, j - 1) + (a[i - 1] == b[j - 1] ? 0 : 1);
            at(i, j) = std::min({at(i - 1, j) + 1, at(i, j - 1) + 1, substitution});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                at(i, j) = std::min(at(i, j), at(i - 2, j - 2) + 1); // "szie" -> "size"
        }
    }
    return at(a.size(), b.size());
}

namespace {

std::string lowercase(std::string_view text) {
    std::string result(text);
    for (char& c : result)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return result;
}

} // namespace

std::optional<std::string> closestMatch(std::string_view word,
                                        const std::vector<std::string>& candidates) {
    // No key is this long; the edit distance would take time and memory
    // in proportion to the word's length.
    constexpr std::size_t kLongestCandidate = 64;
    if (word.size() > kLongestCandidate) return std::nullopt;
    const std::string lower = lowercase(word);
    std::optional<std::string> best;
    std::size_t bestDistance = 0;
    for (const std::string& candidate : candidates) {
        const std::size_t distance = editDistance(lower, lowercase(candidate));
        if (!best || distance < bestDistance) {
            best = candidate;
            bestDistance = distance;
        }
    }
    // Close enough to be a typo: one edit per three characters, at least one.
    const std::size_t allowed = std::max<std::size_t>(1, word.size() / 3);
    if (best && bestDistance <= allowed && bestDistance < best->size()) return best;
    return std::nullopt;
}

std::string escapePointerToken(std::string_view key) {
    std::string token;
    for (const char c : key) {
        if (c == '~')
            token += "~0";
        else if (c == '/')
            token += "~1";
        else
            token += c;
    }
    return token;
}

namespace {

/// The part of an nlohmann message after "[json.exception...] parse error at line L, column C: ".
std::string parserReason(const std::string& what) {
    const std::size_t columnAt = what.find("column ");
    if (columnAt != std::string::npos) {
        const std::size_t colon = what.find(": ", columnAt);
        if (colon != std::string::npos) {
            std::string reason = what.substr(colon + 2);
            constexpr std::string_view kRedundant = "syntax error ";
            if (reason.starts_with(kRedundant)) reason.erase(0, kRedundant.size());
            return reason;
        }
    }
    const std::size_t bracket = what.find("] ");
    return bracket == std::string::npos ? what : what.substr(bracket + 2);
}

} // namespace

nlohmann::json parseJsonText(std::string_view text, const std::string& source) {
    if (text.size() > kMaxSceneBytes)
        throw InputError(source + ": " + std::to_string(text.size() >> 20) +
                         " MiB of JSON, more than the " + std::to_string(kMaxSceneBytes >> 20) +
                         " MiB a scene may hold");
    checkJsonText(text, source, kSceneJsonLimits);
    try {
        return nlohmann::json::parse(text.begin(), text.end());
    } catch (const nlohmann::json::parse_error& e) {
        throw InputError(textLocation(text, e.byte, source) +
                         ": JSON syntax error: " + parserReason(e.what()));
    } catch (const nlohmann::json::exception& e) {
        // A number too large for a double ("number overflow parsing '1e400'"):
        // the parser gives no position, so find the number in the text.
        const std::string what = e.what();
        const std::size_t open = what.find('\'');
        const std::size_t close = what.rfind('\'');
        if (open != std::string::npos && close > open + 1) {
            const std::string token = what.substr(open + 1, close - open - 1);
            const std::size_t at = text.find(token);
            if (at != std::string_view::npos) {
                throw InputError(textLocation(text, at + 1, source) +
                                 ": expected a number that fits a double, got " + token);
            }
        }
        throw InputError(source + ": JSON error: " + parserReason(what));
    }
}

} // namespace cutaway

// The text side of json_reader.hpp: diagnostics, value formatting, typo
// suggestions, and parsing JSON text with positioned syntax errors.
#include "core/error.hpp"
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
    line += pointer.empty() ? std::string_view("(root)") : pointer;
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

std::string describeValue(const nlohmann::json& value, std::size_t maxChars) {
    std::string text = value.is_number_float()
                           ? formatNumber(value.get<double>())
                           : value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    if (text.size() > maxChars && maxChars > 3) {
        text.resize(maxChars - 3);
        // Do not cut a UTF-8 sequence in half.
        while (!text.empty() && (static_cast<unsigned char>(text.back()) & 0xC0) == 0x80)
            text.pop_back();
        if (!text.empty() && (static_cast<unsigned char>(text.back()) & 0x80) != 0) text.pop_back();
        text += "...";
    }
    return text;
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

struct TextPosition {
    std::size_t line = 1;
    std::size_t column = 0;
};

/// Line and column (1-based) after reading the first `count` characters, the
/// way nlohmann counts them (a newline starts line + 1 at column 0).
TextPosition positionAfter(std::string_view text, std::size_t count) {
    TextPosition position;
    for (std::size_t i = 0; i < count; ++i) { // the end of input counts as one character
        if (i < text.size() && text[i] == '\n') {
            ++position.line;
            position.column = 0;
        } else {
            ++position.column;
        }
    }
    return position;
}

std::string located(const std::string& source, TextPosition position) {
    return source + ":" + std::to_string(position.line) + ":" + std::to_string(position.column);
}

/// Rejects documents nested deeper than `maxDepth` without recursing.
void checkNesting(std::string_view text, const std::string& source, int maxDepth) {
    int depth = 0;
    bool inString = false;
    bool escaped = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (escaped)
                escaped = false;
            else if (c == '\\')
                escaped = true;
            else if (c == '"')
                inString = false;
            continue;
        }
        if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            if (++depth > maxDepth) {
                throw InputError(located(source, positionAfter(text, i + 1)) +
                                 ": nesting deeper than " + std::to_string(maxDepth) +
                                 " levels (arrays and objects inside each other)");
            }
        } else if (c == ']' || c == '}') {
            if (depth > 0) --depth; // unbalanced text is left for the parser to report
        }
    }
}

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

nlohmann::json parseJsonText(std::string_view text, const std::string& source, int maxDepth) {
    checkNesting(text, source, maxDepth);
    try {
        return nlohmann::json::parse(text.begin(), text.end());
    } catch (const nlohmann::json::parse_error& e) {
        throw InputError(located(source, positionAfter(text, e.byte)) +
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
                throw InputError(located(source, positionAfter(text, at + 1)) +
                                 ": expected a number that fits a double, got " + token);
            }
        }
        throw InputError(source + ": JSON error: " + parserReason(what));
    }
}

} // namespace cutaway

#pragma once
// Text from a file, quoted for a message: in single quotes, control
// characters and bytes past ASCII written as \xNN (a file cannot put a
// terminal escape sequence on the user's screen), cut after `most`
// characters with "...".
#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>

namespace cutaway {

/// `text` escaped (see above), without the quotes.
inline std::string escapeText(std::string_view text, std::size_t most = 80) {
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (i == most) return out + "...";
        const auto c = static_cast<unsigned char>(text[i]);
        if (c < 0x20 || c >= 0x7f) {
            char hex[8];
            std::snprintf(hex, sizeof hex, "\\x%02x", c);
            out += hex;
        } else {
            out += static_cast<char>(c);
        }
    }
    return out;
}

/// `text` escaped and in single quotes.
inline std::string quoteText(std::string_view text, std::size_t most = 80) {
    std::string out(1, '\'');
    out += escapeText(text, most);
    out += '\'';
    return out;
}

} // namespace cutaway

#include "io/json_limits.hpp"

#include "core/error.hpp"

namespace cutaway {

std::string textLocation(std::string_view text, std::size_t count, const std::string& source) {
    std::size_t line = 1, column = 0;
    for (std::size_t i = 0; i < count; ++i) { // the end of input counts as one character
        if (i < text.size() && text[i] == '\n') {
            ++line;
            column = 0;
        } else {
            ++column;
        }
    }
    return source + ":" + std::to_string(line) + ":" + std::to_string(column);
}

void checkJsonText(std::string_view text, const std::string& source, const JsonLimits& limits) {
    int depth = 0;
    bool inString = false;
    bool escaped = false;
    std::size_t stringStart = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (c == '"' && !escaped) {
                inString = false;
                continue;
            }
            escaped = !escaped && c == '\\';
            if (i + 1 - stringStart > limits.maxStringBytes) // the bytes up to c
                throw InputError(textLocation(text, stringStart, source) +
                                 ": a string longer than " +
                                 std::to_string(limits.maxStringBytes >> 10) +
                                 " KiB, more than any value here may hold");
            continue;
        }
        if (c == '"') {
            inString = true;
            stringStart = i + 1;
        } else if (c == '[' || c == '{') {
            if (++depth > limits.maxDepth) {
                throw InputError(textLocation(text, i + 1, source) + ": nesting deeper than " +
                                 std::to_string(limits.maxDepth) +
                                 " levels (arrays and objects inside each other)");
            }
        } else if (c == ']' || c == '}') {
            if (depth > 0) --depth; // unbalanced text is left for the parser to report
        }
    }
}

} // namespace cutaway

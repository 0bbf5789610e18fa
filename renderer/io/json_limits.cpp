#include "io/json_limits.hpp"

#include "core/error.hpp"

#include <map>
#include <vector>

namespace cutaway {
namespace {

// An array or object the scan is inside: where its pointer stands (the key
// or index of the value being read) and, for an object, the keys seen.
struct Container {
    bool object = false;
    bool expectKey = false;                  // an object's next string is a key
    std::size_t index = 0;                   // an array's current element
    std::string key;                         // an object's current key, as written
    std::map<std::string, std::size_t> keys; // each key's offset in the text
};

// The JSON pointer of the value being read, `~` and `/` escaped (keys as
// written: a key with escapes of its own keeps them).
std::string pointerOf(const std::vector<Container>& stack) {
    std::string pointer;
    for (const Container& c : stack) {
        if (!c.object) {
            pointer += "/" + std::to_string(c.index);
            continue;
        }
        pointer += "/";
        for (char ch : c.key)
            pointer += ch == '~'   ? std::string("~0")
                       : ch == '/' ? std::string("~1")
                                   : std::string(1, ch);
    }
    return pointer;
}

// A key that ends at text[end] (its closing quote), begun at `start`.
void keyRead(std::vector<Container>& stack, std::string_view text, std::size_t start,
             std::size_t end, const std::string& source) {
    Container& c = stack.back();
    c.key.assign(text.substr(start, end - start));
    c.expectKey = false;
    const auto [at, fresh] = c.keys.emplace(c.key, start);
    if (fresh) return;
    throw InputError(textLocation(text, start, source) + ": " + pointerOf(stack) + ": the key \"" +
                     c.key + "\" is written twice in one object (first at " +
                     textLocation(text, at->second, source).substr(source.size() + 1) +
                     "); a scene says each thing once");
}

} // namespace

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
    bool inKey = false;
    bool escaped = false;
    std::size_t stringStart = 0;
    std::vector<Container> stack; // with uniqueKeys only
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (c == '"' && !escaped) {
                inString = false;
                if (inKey) keyRead(stack, text, stringStart, i, source);
                inKey = false;
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
            inKey = limits.uniqueKeys && !stack.empty() && stack.back().expectKey;
        } else if (c == '[' || c == '{') {
            if (++depth > limits.maxDepth) {
                throw InputError(textLocation(text, i + 1, source) + ": nesting deeper than " +
                                 std::to_string(limits.maxDepth) +
                                 " levels (arrays and objects inside each other)");
            }
            if (limits.uniqueKeys) stack.push_back({c == '{', c == '{'});
        } else if (c == ']' || c == '}') {
            if (depth > 0) --depth; // unbalanced text is left for the parser to report
            if (!stack.empty()) stack.pop_back();
        } else if (c == ',' && !stack.empty()) {
            ++stack.back().index;
            stack.back().expectKey = stack.back().object;
        }
    }
}

} // namespace cutaway

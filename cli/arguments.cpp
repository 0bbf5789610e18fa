#include "arguments.hpp"

#include "core/error.hpp"

#include <regex>

namespace cutaway::cli {

glm::ivec2 parseSize(const std::string& text) {
    static const std::regex form("([0-9]{1,5})x([0-9]{1,5})");
    std::smatch m;
    if (!std::regex_match(text, m, form))
        throw InputError("--size: expected WIDTHxHEIGHT such as 512x512, got \"" + text + "\"");
    glm::ivec2 size(std::stoi(m[1].str()), std::stoi(m[2].str()));
    if (size.x < 1 || size.y < 1 || size.x > 16384 || size.y > 16384)
        throw InputError("--size: each side must be in [1, 16384], got " + text);
    return size;
}

} // namespace cutaway::cli

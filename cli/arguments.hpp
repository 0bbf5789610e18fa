#pragma once
// Parsing of option values several subcommands share.
#include <glm/glm.hpp>
#include <string>

namespace cutaway::cli {

/// --size WIDTHxHEIGHT, each in [1, 16384]; InputError naming --size otherwise.
glm::ivec2 parseSize(const std::string& text);

} // namespace cutaway::cli

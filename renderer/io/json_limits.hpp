#pragma once
// Bounds on JSON text, checked on the text itself before any parser reads it:
// nlohmann (scenes, --set values) and tinygltf (glTF files and the JSON chunk
// of .glb files) recurse once per level of nesting, and a hostile document
// of a few kilobytes would otherwise overflow the stack. The scan is one
// pass, without recursion or allocation.
#include <cstddef>
#include <string>
#include <string_view>

namespace cutaway {

/// Arrays and objects inside each other: no format cutaway reads needs more.
inline constexpr int kMaxJsonDepth = 64;
/// The largest scene file (or --set value): far beyond a scene of thousands
/// of tracks and keys, small enough to parse in a moment.
inline constexpr std::size_t kMaxSceneBytes = std::size_t{64} << 20;
/// The longest string a scene holds (a key, a path, a pattern), as written.
inline constexpr std::size_t kMaxSceneStringBytes = std::size_t{1} << 20;

struct JsonLimits {
    int maxDepth = kMaxJsonDepth;
    std::size_t maxStringBytes = static_cast<std::size_t>(-1); ///< no bound by default
    /// Refuse a key written twice in one object (a parser keeps one of them
    /// silently). Keys are compared as written, escapes and all.
    bool uniqueKeys = false;
};

/// Bounds of a scene's text: scene files and --set values.
inline constexpr JsonLimits kSceneJsonLimits{kMaxJsonDepth, kMaxSceneStringBytes, true};

/// Throws InputError "SOURCE:LINE:COLUMN: ..." at the first place where
/// `text` nests deeper than the limits allow, holds a longer string, or
/// (with uniqueKeys) repeats a key in one object: that error names the JSON
/// pointer and both places.
/// Unbalanced or otherwise malformed text is left for the parser to report.
void checkJsonText(std::string_view text, const std::string& source, const JsonLimits& limits);

/// "SOURCE:LINE:COLUMN" of the place after the first `count` bytes of
/// `text` (1-based lines; a newline starts the next line at column 0, as
/// nlohmann counts).
std::string textLocation(std::string_view text, std::size_t count, const std::string& source);

} // namespace cutaway

#pragma once
// Label tables as atlases and tools ship them: a name and a colour per label
// id, one label per line, `#` starting a comment.
//
//   FreeSurfer *ColorLUT.txt, 3D Slicer .ctbl/.txt, plain lists:
//       id name [r g b [a]]          (r, g, b, a integers in [0, 255])
//   ITK-SNAP label descriptions:
//       id r g b a visible mesh "name"   (a in [0, 1]; the name quoted)
//
// A line's form is told by its quotes. Lines without a colour give none.
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <map>
#include <optional>
#include <string>

namespace cutaway {

struct LabelTable {
    std::map<std::string, std::int64_t> names; ///< name -> id (each name once)
    /// id -> linear RGB: the table's bytes are sRGB (as atlases and viewers
    /// show them), decoded, so a PNG shows the table's own bytes.
    std::map<std::int64_t, glm::vec3> colors;
};

/// The palette of "color": "auto": Kelly's twenty-two colours of maximum
/// contrast (1965) without white and black, 20 colours, as linear RGB;
/// `index` cycles through them.
glm::vec3 paletteColour(std::size_t index);
inline constexpr std::size_t kPaletteColours = 20;

/// Reads a table; throws InputError naming the file and the line of a line
/// that is neither form, an id outside [0, 2^31 - 1] or a colour outside
/// [0, 255], an id or a name a line before gave, and a file of more than
/// 16 MiB or with no label.
LabelTable readLabelTable(const std::filesystem::path& path);

} // namespace cutaway

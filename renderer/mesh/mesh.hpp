#pragma once
// Triangle meshes drawn with the volume: glTF tool models (paper Fig. 10) and
// the built-in operator glyphs (Fig. 8). Plain CPU data; render/ uploads it.
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cutaway::mesh {

/// An indexed triangle list. Positions are in the model's own units and frame;
/// normals are unit length, one per vertex; colours are linear RGBA, one per
/// vertex (the material's base colour, times COLOR_0 where the model has it).
struct TriangleMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec4> colors;
    std::vector<std::uint32_t> indices; ///< three per triangle
    glm::vec3 lo{0.0f}, hi{0.0f};       ///< bounds of the positions

    std::size_t triangleCount() const { return indices.size() / 3; }
    /// Appends another mesh (indices are offset); bounds are updated.
    void append(const TriangleMesh& other);
};

/// Reads a glTF 2.0 file (.gltf with its buffers, or .glb): every triangle
/// primitive of the default scene's nodes, with node transforms applied.
/// Throws InputError naming the file and what is wrong with it. The model
/// and every file it names are read as io/input_file.hpp reads inputs
/// (regular files only, never blocking), each up to 1 GiB, and its JSON is
/// nested no deeper than io/json_limits.hpp allows.
TriangleMesh loadGltf(const std::filesystem::path& file);

/// The same for a model's bytes in memory (.glb when they start with its
/// magic, else .gltf JSON), `name` standing for the file in messages. The
/// files it names are read from `folder`; without one it names none (only
/// data URIs and the .glb's own buffer are read).
TriangleMesh loadGltfBytes(std::string_view bytes, const std::string& name,
                           const std::optional<std::filesystem::path>& folder = std::nullopt);

/// The files reading `file` reads: the model, then the buffers and images it
/// names. Throws as loadGltf does when the model cannot be read.
std::vector<std::filesystem::path> gltfFiles(const std::filesystem::path& file);

/// The outline of the box [lo, hi]: its 12 edges as square bars `width` thick
/// (so the lines keep their width at any image size), flat-shaded, one colour.
TriangleMesh boxOutline(glm::vec3 lo, glm::vec3 hi, float width, glm::vec4 color);

} // namespace cutaway::mesh

#pragma once
// The glTF loader's parts (private to mesh/). A model file is untrusted
// input: every index and byte range is validated before a byte of a buffer is
// read, and errors name the accessor, the view and the buffer.
#include "mesh/mesh.hpp"

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace cutaway::mesh::detail {

// `what` starts each message and names the attribute, e.g.
// "tool.glb: mesh 0 primitive 1: POSITION"; the accessor index follows it.

/// A float VEC3 accessor (POSITION, NORMAL); non-finite values are errors.
std::vector<glm::vec3> readVec3(const tinygltf::Model& model, int accessor,
                                const std::string& what);

/// COLOR_0: float, or (normalized) unsigned byte or short; VEC3 (alpha 1) or VEC4.
std::vector<glm::vec4> readColors(const tinygltf::Model& model, int accessor,
                                  const std::string& what);

/// Vertex indices: unsigned byte, short or int SCALAR.
std::vector<std::uint32_t> readIndices(const tinygltf::Model& model, int accessor,
                                       const std::string& what);

/// Appends primitive `primIndex` of mesh `meshIndex` (both valid) to `out`,
/// transformed by `toWorld`. Points and lines, and primitives without
/// POSITION, are skipped; strips and fans become triangle lists. Without
/// NORMAL, triangles get flat normals (and their own vertices), as glTF asks.
void addPrimitive(TriangleMesh& out, const tinygltf::Model& model, int meshIndex, int primIndex,
                  const glm::mat4& toWorld, const std::string& ctx);

} // namespace cutaway::mesh::detail

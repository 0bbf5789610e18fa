// One glTF primitive into the output mesh: attributes read and checked,
// transformed to the scene's frame, normals completed.
#include "core/error.hpp"
#include "mesh/gltf_detail.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tiny_gltf.h>

namespace cutaway::mesh::detail {
namespace {

glm::vec3 unitOr(glm::vec3 v, glm::vec3 fallback) {
    const float len = glm::length(v);
    return std::isfinite(len) && len > 1e-30f ? v / len : fallback;
}

glm::vec3 faceNormal(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    return unitOr(glm::cross(b - a, c - a), glm::vec3(0.0f, 0.0f, 1.0f));
}

// Strips and fans become lists; strip triangles alternate so that all keep
// the first one's winding.
std::vector<std::uint32_t> triangleList(std::vector<std::uint32_t> corners, int mode,
                                        const std::string& what) {
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (corners.size() % 3 != 0) {
            throw InputError(what + ": " + std::to_string(corners.size()) +
                             " vertices do not make whole triangles");
        }
        return corners;
    }
    std::vector<std::uint32_t> tris;
    for (std::size_t i = 2; i < corners.size(); ++i) {
        const std::uint32_t a = mode == TINYGLTF_MODE_TRIANGLE_FAN ? corners[0] : corners[i - 2];
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP && i % 2 == 1)
            tris.insert(tris.end(), {corners[i - 1], a, corners[i]});
        else
            tris.insert(tris.end(), {a, corners[i - 1], corners[i]});
    }
    return tris;
}

} // namespace

void addPrimitive(TriangleMesh& out, const tinygltf::Model& model, int meshIndex, int primIndex,
                  const glm::mat4& toWorld, const std::string& ctx) {
    const tinygltf::Primitive& prim = model.meshes[meshIndex].primitives[primIndex];
    const std::string what =
        ctx + ": mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(primIndex);
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    // Points and lines have no surface to draw; the spec says to skip
    // primitives without positions.
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN)
        return;
    const auto attribute = [&](const char* name) {
        const auto it = prim.attributes.find(name);
        return it == prim.attributes.end() ? -1 : it->second;
    };
    const int positionAccessor = attribute("POSITION");
    if (positionAccessor < 0) return;
    std::vector<glm::vec3> positions = readVec3(model, positionAccessor, what + ": POSITION");

    std::vector<std::uint32_t> corners;
    if (prim.indices != -1) {
        corners = readIndices(model, prim.indices, what + ": indices");
        for (std::size_t i = 0; i < corners.size(); ++i) {
            if (corners[i] >= positions.size()) {
                throw InputError(what + ": indices accessor " + std::to_string(prim.indices) +
                                 ": index " + std::to_string(corners[i]) + " (element " +
                                 std::to_string(i) + ") is out of range: POSITION has " +
                                 std::to_string(positions.size()) + " vertices");
            }
        }
    } else {
        if (positions.size() > std::numeric_limits<std::uint32_t>::max())
            throw InputError(what + ": more than 2^32 vertices");
        corners.resize(positions.size());
        for (std::size_t i = 0; i < corners.size(); ++i)
            corners[i] = static_cast<std::uint32_t>(i);
    }
    std::vector<std::uint32_t> tris = triangleList(std::move(corners), mode, what);
    if (tris.empty()) return;

    const auto sameCount = [&](std::size_t n, const char* name, int accessor) {
        if (n != positions.size()) {
            throw InputError(what + ": " + name + " accessor " + std::to_string(accessor) +
                             " has " + std::to_string(n) + " elements, POSITION has " +
                             std::to_string(positions.size()));
        }
    };
    std::vector<glm::vec3> normals;
    if (const int a = attribute("NORMAL"); a >= 0) {
        normals = readVec3(model, a, what + ": NORMAL");
        sameCount(normals.size(), "NORMAL", a);
    }
    glm::vec4 base(1.0f);
    if (prim.material != -1) {
        if (prim.material < 0 || static_cast<std::size_t>(prim.material) >= model.materials.size())
            throw InputError(what + ": material " + std::to_string(prim.material) +
                             " does not exist");
        const std::vector<double>& f =
            model.materials[prim.material].pbrMetallicRoughness.baseColorFactor;
        if (f.size() != 4) {
            throw InputError(what + ": material " + std::to_string(prim.material) +
                             ": baseColorFactor must have 4 numbers");
        }
        base = glm::vec4(static_cast<float>(f[0]), static_cast<float>(f[1]),
                         static_cast<float>(f[2]), static_cast<float>(f[3]));
    }
    std::vector<glm::vec4> colors(positions.size(), base);
    if (const int a = attribute("COLOR_0"); a >= 0) {
        const std::vector<glm::vec4> c = readColors(model, a, what + ": COLOR_0");
        sameCount(c.size(), "COLOR_0", a);
        for (std::size_t i = 0; i < c.size(); ++i)
            colors[i] *= c[i];
    }

    for (glm::vec3& p : positions) {
        p = glm::vec3(toWorld * glm::vec4(p, 1.0f));
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw InputError(what + ": the node transforms give non-finite positions");
    }
    const glm::mat3 linear(toWorld);
    const float det = glm::determinant(linear);
    // A mirroring transform turns counter-clockwise triangles clockwise.
    if (det < 0.0f) {
        for (std::size_t t = 0; t < tris.size(); t += 3)
            std::swap(tris[t + 1], tris[t + 2]);
    }

    TriangleMesh piece;
    if (normals.empty()) {
        // glTF asks for flat normals here, so each triangle gets its own vertices.
        for (std::size_t t = 0; t < tris.size(); t += 3) {
            const glm::vec3 n =
                faceNormal(positions[tris[t]], positions[tris[t + 1]], positions[tris[t + 2]]);
            for (int k = 0; k < 3; ++k) {
                piece.positions.push_back(positions[tris[t + k]]);
                piece.colors.push_back(colors[tris[t + k]]);
                piece.normals.push_back(n);
                piece.indices.push_back(static_cast<std::uint32_t>(t + k));
            }
        }
    } else {
        // The cofactor matrix is det * inverse-transpose: no inverse needed,
        // and it still gives directions for a singular transform.
        const glm::mat3 cofactor(glm::cross(linear[1], linear[2]), glm::cross(linear[2], linear[0]),
                                 glm::cross(linear[0], linear[1]));
        const float sign = det < 0.0f ? -1.0f : 1.0f;
        const glm::vec3 bad(0.0f);
        for (glm::vec3& n : normals)
            n = unitOr(sign * (cofactor * n), bad);
        // Zero normals (in the file, or squashed flat) take a face's normal.
        for (std::size_t t = 0; t < tris.size(); t += 3) {
            for (int k = 0; k < 3; ++k) {
                if (normals[tris[t + k]] == bad) {
                    normals[tris[t + k]] = faceNormal(positions[tris[t]], positions[tris[t + 1]],
                                                      positions[tris[t + 2]]);
                }
            }
        }
        std::replace(normals.begin(), normals.end(), bad, glm::vec3(0.0f, 0.0f, 1.0f));
        piece.positions = std::move(positions);
        piece.normals = std::move(normals);
        piece.colors = std::move(colors);
        piece.indices = std::move(tris);
    }
    if (out.positions.size() + piece.positions.size() > std::numeric_limits<std::uint32_t>::max())
        throw InputError(ctx + ": more than 2^32 vertices");
    out.append(piece);
}

} // namespace cutaway::mesh::detail

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

// The primitive's corners, as indices into its positions (its own, or
// 0..n-1 without an index accessor), each checked against their count.
std::vector<std::uint32_t> primitiveCorners(const tinygltf::Model& model,
                                            const tinygltf::Primitive& prim, std::size_t vertices,
                                            const std::string& what) {
    std::vector<std::uint32_t> corners;
    if (prim.indices == -1) {
        if (vertices > std::numeric_limits<std::uint32_t>::max())
            throw InputError(what + ": more than 2^32 vertices");
        corners.resize(vertices);
        for (std::size_t i = 0; i < corners.size(); ++i)
            corners[i] = static_cast<std::uint32_t>(i);
        return corners;
    }
    corners = readIndices(model, prim.indices, what + ": indices");
    for (std::size_t i = 0; i < corners.size(); ++i) {
        if (corners[i] >= vertices) {
            throw InputError(what + ": indices accessor " + std::to_string(prim.indices) +
                             ": index " + std::to_string(corners[i]) + " (element " +
                             std::to_string(i) + ") is out of range: POSITION has " +
                             std::to_string(vertices) + " vertices");
        }
    }
    return corners;
}

// The material's base colour factor (white without a material).
glm::vec4 baseColor(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                    const std::string& what) {
    if (prim.material == -1) return glm::vec4(1.0f);
    if (prim.material < 0 || static_cast<std::size_t>(prim.material) >= model.materials.size())
        throw InputError(what + ": material " + std::to_string(prim.material) + " does not exist");
    const std::vector<double>& f =
        model.materials[prim.material].pbrMetallicRoughness.baseColorFactor;
    if (f.size() != 4) {
        throw InputError(what + ": material " + std::to_string(prim.material) +
                         ": baseColorFactor must have 4 numbers");
    }
    return glm::vec4(static_cast<float>(f[0]), static_cast<float>(f[1]), static_cast<float>(f[2]),
                     static_cast<float>(f[3]));
}

// A primitive's vertices as read: positions, normals (maybe none) and colours.
struct Vertices {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec4> colors;
};

// The NORMAL and COLOR_0 attributes where present, each as many as the
// positions; the colours times the material's base colour.
void readAttributes(Vertices& v, const tinygltf::Model& model, const tinygltf::Primitive& prim,
                    const std::string& what) {
    const auto attribute = [&](const char* name) {
        const auto it = prim.attributes.find(name);
        return it == prim.attributes.end() ? -1 : it->second;
    };
    const auto sameCount = [&](std::size_t n, const char* name, int accessor) {
        if (n != v.positions.size()) {
            throw InputError(what + ": " + name + " accessor " + std::to_string(accessor) +
                             " has " + std::to_string(n) + " elements, POSITION has " +
                             std::to_string(v.positions.size()));
        }
    };
    if (const int a = attribute("NORMAL"); a >= 0) {
        v.normals = readVec3(model, a, what + ": NORMAL");
        sameCount(v.normals.size(), "NORMAL", a);
    }
    v.colors.assign(v.positions.size(), baseColor(model, prim, what));
    if (const int a = attribute("COLOR_0"); a >= 0) {
        const std::vector<glm::vec4> c = readColors(model, a, what + ": COLOR_0");
        sameCount(c.size(), "COLOR_0", a);
        for (std::size_t i = 0; i < c.size(); ++i)
            v.colors[i] *= c[i];
    }
}

// The triangles `tris` of `v` (in the scene's frame, transformed by
// `linear`) as a mesh: with flat normals where the file has none (glTF asks
// for them, so each triangle gets its own vertices), else with the file's
// normals transformed, zero ones taking a face's.
TriangleMesh meshOf(Vertices v, std::vector<std::uint32_t> tris, const glm::mat3& linear) {
    TriangleMesh piece;
    if (v.normals.empty()) {
        for (std::size_t t = 0; t < tris.size(); t += 3) {
            const glm::vec3 n = faceNormal(v.positions[tris[t]], v.positions[tris[t + 1]],
                                           v.positions[tris[t + 2]]);
            for (int k = 0; k < 3; ++k) {
                piece.positions.push_back(v.positions[tris[t + k]]);
                piece.colors.push_back(v.colors[tris[t + k]]);
                piece.normals.push_back(n);
                piece.indices.push_back(static_cast<std::uint32_t>(t + k));
            }
        }
        return piece;
    }
    // The cofactor matrix is det * inverse-transpose: no inverse needed, and
    // it still gives directions for a singular transform.
    const glm::mat3 cofactor(glm::cross(linear[1], linear[2]), glm::cross(linear[2], linear[0]),
                             glm::cross(linear[0], linear[1]));
    const float sign = glm::determinant(linear) < 0.0f ? -1.0f : 1.0f;
    const glm::vec3 bad(0.0f);
    for (glm::vec3& n : v.normals)
        n = unitOr(sign * (cofactor * n), bad);
    // Zero normals (in the file, or squashed flat) take a face's normal.
    for (std::size_t t = 0; t < tris.size(); t += 3) {
        for (int k = 0; k < 3; ++k) {
            if (v.normals[tris[t + k]] == bad) {
                v.normals[tris[t + k]] = faceNormal(v.positions[tris[t]], v.positions[tris[t + 1]],
                                                    v.positions[tris[t + 2]]);
            }
        }
    }
    std::replace(v.normals.begin(), v.normals.end(), bad, glm::vec3(0.0f, 0.0f, 1.0f));
    piece.positions = std::move(v.positions);
    piece.normals = std::move(v.normals);
    piece.colors = std::move(v.colors);
    piece.indices = std::move(tris);
    return piece;
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
    const auto position = prim.attributes.find("POSITION");
    if (position == prim.attributes.end() || position->second < 0) return;
    Vertices v;
    v.positions = readVec3(model, position->second, what + ": POSITION");
    std::vector<std::uint32_t> tris =
        triangleList(primitiveCorners(model, prim, v.positions.size(), what), mode, what);
    if (tris.empty()) return;
    readAttributes(v, model, prim, what);

    for (glm::vec3& p : v.positions) {
        p = glm::vec3(toWorld * glm::vec4(p, 1.0f));
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw InputError(what + ": the node transforms give non-finite positions");
    }
    const glm::mat3 linear(toWorld);
    // A mirroring transform turns counter-clockwise triangles clockwise.
    if (glm::determinant(linear) < 0.0f) {
        for (std::size_t t = 0; t < tris.size(); t += 3)
            std::swap(tris[t + 1], tris[t + 2]);
    }
    const TriangleMesh piece = meshOf(std::move(v), std::move(tris), linear);
    if (out.positions.size() + piece.positions.size() > std::numeric_limits<std::uint32_t>::max())
        throw InputError(ctx + ": more than 2^32 vertices");
    out.append(piece);
}

} // namespace cutaway::mesh::detail

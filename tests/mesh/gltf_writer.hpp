#pragma once
// Small glTF files written by the loader tests: a JSON body plus one binary
// buffer, as .gltf (the buffer as a base64 data URI) or .glb (a BIN chunk),
// and checks shared by the mesh tests.
#include "mesh/mesh.hpp"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <vector>

namespace cutaway::test {

/// A temporary folder of its own for one test, removed afterwards.
class TempDir {
public:
    TempDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        m_path = std::filesystem::temp_directory_path() /
                 ("cutaway_mesh_" + std::string(info ? info->name() : "test") + "_" +
                  std::to_string(std::random_device{}()));
        std::filesystem::create_directories(m_path);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(m_path, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    std::filesystem::path operator/(const std::string& name) const { return m_path / name; }

private:
    std::filesystem::path m_path;
};

/// Buffer 0's bytes; add() appends 4-byte aligned and returns the offset.
struct Bin {
    std::vector<unsigned char> bytes;

    template <typename T>
    std::size_t add(const std::vector<T>& values) {
        bytes.resize((bytes.size() + 3) / 4 * 4, 0);
        const std::size_t offset = bytes.size();
        bytes.resize(offset + values.size() * sizeof(T));
        std::memcpy(bytes.data() + offset, values.data(), values.size() * sizeof(T));
        return offset;
    }
};

inline std::string base64(const std::vector<unsigned char>& data) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < data.size(); i += 3) {
        unsigned v = static_cast<unsigned>(data[i]) << 16;
        if (i + 1 < data.size()) v |= static_cast<unsigned>(data[i + 1]) << 8;
        if (i + 2 < data.size()) v |= data[i + 2];
        out += digits[(v >> 18) & 63];
        out += digits[(v >> 12) & 63];
        out += i + 1 < data.size() ? digits[(v >> 6) & 63] : '=';
        out += i + 2 < data.size() ? digits[v & 63] : '=';
    }
    return out;
}

/// The whole document: `body` holds the members after "asset" and
/// "buffers", e.g. "\"nodes\": [...], \"meshes\": [...]".
inline std::string gltfJson(const std::string& body, const Bin& bin, bool dataUri) {
    std::string buffer = "{\"byteLength\": " + std::to_string(bin.bytes.size());
    if (dataUri)
        buffer += ", \"uri\": \"data:application/octet-stream;base64," + base64(bin.bytes) + "\"";
    return "{\"asset\": {\"version\": \"2.0\"}, \"buffers\": [" + buffer + "}], " + body + "}";
}

inline void writeBytes(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
    ASSERT_TRUE(out.good()) << path;
}

inline void writeText(const std::filesystem::path& path, const std::string& text) {
    writeBytes(path, std::vector<unsigned char>(text.begin(), text.end()));
}

inline void writeGltf(const std::filesystem::path& path, const std::string& body, const Bin& bin) {
    writeText(path, gltfJson(body, bin, true));
}

inline std::vector<unsigned char> glbBytes(const std::string& body, const Bin& bin) {
    std::string json = gltfJson(body, bin, false);
    json.resize((json.size() + 3) / 4 * 4, ' ');
    std::vector<unsigned char> data = bin.bytes;
    data.resize((data.size() + 3) / 4 * 4, 0);
    std::vector<unsigned char> out;
    const auto u32 = [&](std::uint32_t v) {
        for (int i = 0; i < 4; ++i)
            out.push_back(static_cast<unsigned char>(v >> (8 * i)));
    };
    out.insert(out.end(), {'g', 'l', 'T', 'F'});
    u32(2);
    u32(static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + data.size()));
    u32(static_cast<std::uint32_t>(json.size()));
    out.insert(out.end(), {'J', 'S', 'O', 'N'});
    out.insert(out.end(), json.begin(), json.end());
    u32(static_cast<std::uint32_t>(data.size()));
    out.insert(out.end(), {'B', 'I', 'N', '\0'});
    out.insert(out.end(), data.begin(), data.end());
    return out;
}

inline void writeGlb(const std::filesystem::path& path, const std::string& body, const Bin& bin) {
    writeBytes(path, glbBytes(body, bin));
}

/// The corners of triangle t.
inline std::vector<glm::vec3> corners(const mesh::TriangleMesh& m, std::size_t t) {
    return {m.positions[m.indices[3 * t]], m.positions[m.indices[3 * t + 1]],
            m.positions[m.indices[3 * t + 2]]};
}

inline glm::vec3 geometricNormal(const mesh::TriangleMesh& m, std::size_t t) {
    const std::vector<glm::vec3> c = corners(m, t);
    return glm::normalize(glm::cross(c[1] - c[0], c[2] - c[0]));
}

/// Every edge, by position, is used once in each direction: the mesh is a
/// union of closed surfaces with consistent winding. Positions are rounded to
/// `grid` so that separate vertices at the same place count as one.
inline bool closedAndConsistent(const mesh::TriangleMesh& m, float grid) {
    using Key = std::tuple<long, long, long>;
    const auto key = [&](glm::vec3 p) {
        return Key{std::lround(p.x / grid), std::lround(p.y / grid), std::lround(p.z / grid)};
    };
    std::map<std::pair<Key, Key>, int> balance;
    for (std::size_t t = 0; t < m.triangleCount(); ++t) {
        const std::vector<glm::vec3> c = corners(m, t);
        for (int k = 0; k < 3; ++k) {
            const Key a = key(c[k]), b = key(c[(k + 1) % 3]);
            if (a == b) continue;
            if (a < b)
                ++balance[{a, b}];
            else
                --balance[{b, a}];
        }
    }
    for (const auto& [edge, count] : balance) {
        if (count != 0) return false;
    }
    return true;
}

} // namespace cutaway::test

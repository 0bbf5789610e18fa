// loadGltf on files the tests write by hand: node transforms, .gltf against
// .glb, index types, colours, computed normals; and the committed tool models.
#include "gltf_writer.hpp"

#include <array>

namespace cutaway::test {
namespace {

using mesh::TriangleMesh;

std::string num(std::size_t v) {
    return std::to_string(v);
}

// One triangle (0,0,0) (1,0,0) (0,1,0) with the deliberately tilted normal
// (1,0,1)/sqrt 2, placed by a node tree: node 0 translates by (10,0,0); its
// child 1 rotates 90 degrees about z and scales by (2,3,4); its child 2 is a
// matrix mirroring x and translating by (0,0,5). Scene 1 is the default;
// scene 0 holds a decoy node far away.
std::string hierarchyBody(Bin& bin) {
    const float s = std::sqrt(0.5f);
    const std::size_t pos = bin.add(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
    const std::size_t nrm = bin.add(std::vector<float>{s, 0, s, s, 0, s, s, 0, s});
    return R"("scene": 1, "scenes": [{"nodes": [3]}, {"nodes": [0]}],
      "nodes": [{"translation": [10, 0, 0], "children": [1, 2]},
                {"rotation": [0, 0, 0.70710678, 0.70710678], "scale": [2, 3, 4], "mesh": 0},
                {"matrix": [-1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,5,1], "mesh": 0},
                {"translation": [-100, 0, 0], "mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}}]}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
         "min": [0, 0, 0], "max": [1, 1, 0]},
        {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"}],
      "bufferViews": [{"buffer": 0, "byteOffset": )" +
           num(pos) + R"(, "byteLength": 36},
                      {"buffer": 0, "byteOffset": )" +
           num(nrm) + R"(, "byteLength": 36}])";
}

void expectNear(glm::vec3 got, glm::vec3 want, const std::string& what) {
    EXPECT_NEAR(glm::distance(got, want), 0.0f, 1e-5f)
        << what << ": got " << got.x << " " << got.y << " " << got.z;
}

// Triangle t has corners `want` in this order, up to a cyclic shift (which
// keeps the winding).
void expectTriangle(const TriangleMesh& m, std::size_t t, std::array<glm::vec3, 3> want) {
    const std::vector<glm::vec3> got = corners(m, t);
    for (int shift = 0; shift < 3; ++shift) {
        if (glm::distance(got[shift], want[0]) < 1e-5f) {
            for (int k = 0; k < 3; ++k)
                expectNear(got[(shift + k) % 3], want[k], "triangle " + num(t));
            return;
        }
    }
    ADD_FAILURE() << "triangle " << t << " lacks corner " << want[0].x << " " << want[0].y;
}

TEST(Gltf, NodeTreeTransformsPositionsAndNormals) {
    TempDir dir;
    Bin bin;
    const std::string body = hierarchyBody(bin);
    writeGltf(dir / "tree.gltf", body, bin);
    const TriangleMesh m = mesh::loadGltf(dir / "tree.gltf");
    ASSERT_EQ(m.triangleCount(), 2u);
    ASSERT_EQ(m.positions.size(), 6u);
    // Node 1: T(10,0,0) R_z(90) S(2,3,4).
    expectTriangle(m, 0, {{{10, 0, 0}, {10, 2, 0}, {7, 0, 0}}});
    // Node 2 mirrors x, so its triangle's winding is reversed to stay
    // counter-clockwise from the side its normals face.
    expectTriangle(m, 1, {{{10, 0, 5}, {10, 1, 5}, {9, 0, 5}}});
    // Normals go through the inverse-transpose: R S^-1 n, renormalized.
    for (int v = 0; v < 3; ++v)
        expectNear(m.normals[m.indices[v]], glm::normalize(glm::vec3(0, 2, 1)), "normal");
    for (int v = 3; v < 6; ++v)
        expectNear(m.normals[m.indices[v]], glm::normalize(glm::vec3(-1, 0, 1)), "mirrored");
    for (std::size_t t = 0; t < 2; ++t) {
        for (int k = 0; k < 3; ++k)
            EXPECT_GT(glm::dot(geometricNormal(m, t), m.normals[m.indices[3 * t + k]]), 0.0f);
    }
    expectNear(m.lo, {7, 0, 0}, "lo");
    expectNear(m.hi, {10, 2, 5}, "hi");
    for (const glm::vec4& c : m.colors)
        EXPECT_EQ(c, glm::vec4(1.0f)); // no material: white
}

TEST(Gltf, GlbGivesTheSameMeshAsGltf) {
    TempDir dir;
    Bin bin;
    const std::string body = hierarchyBody(bin);
    writeGltf(dir / "tree.gltf", body, bin);
    writeGlb(dir / "tree.glb", body, bin);
    const TriangleMesh a = mesh::loadGltf(dir / "tree.gltf");
    const TriangleMesh b = mesh::loadGltf(dir / "tree.glb");
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.normals, b.normals);
    EXPECT_EQ(a.colors, b.colors);
    EXPECT_EQ(a.indices, b.indices);
    EXPECT_EQ(a.lo, b.lo);
    EXPECT_EQ(a.hi, b.hi);
}

// A quad from interleaved positions and normals (stride 24), its indices in
// each unsigned type, after a few bytes of padding (accessor byteOffset).
TEST(Gltf, ReadsEveryIndexTypeAndInterleavedVertices) {
    const std::vector<glm::vec3> quad = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const std::vector<std::uint32_t> order = {3, 0, 1, 3, 1, 2};
    for (int type : {5121, 5123, 5125}) {
        TempDir dir;
        Bin bin;
        std::vector<float> interleaved;
        for (glm::vec3 p : quad)
            interleaved.insert(interleaved.end(), {p.x, p.y, p.z, 0, 0, 1});
        const std::size_t vertices = bin.add(interleaved);
        std::size_t idx = 0, size = 0;
        if (type == 5121) {
            idx = bin.add(std::vector<std::uint8_t>{0, 0, 0, 0, 3, 0, 1, 3, 1, 2});
            size = 1;
        } else if (type == 5123) {
            idx = bin.add(std::vector<std::uint16_t>{0, 0, 3, 0, 1, 3, 1, 2});
            size = 2;
        } else {
            idx = bin.add(std::vector<std::uint32_t>{0, 3, 0, 1, 3, 1, 2});
            size = 4;
        }
        const std::string body =
            R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1},
                "indices": 2, "mode": 4}]}], "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}],
              "accessors": [
                {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
                {"bufferView": 0, "byteOffset": 12, "componentType": 5126, "count": 4, "type": "VEC3"},
                {"bufferView": 1, "byteOffset": 4, "componentType": )" +
            std::to_string(type) + R"(, "count": 6, "type": "SCALAR"}],
              "bufferViews": [
                {"buffer": 0, "byteOffset": )" +
            num(vertices) + R"(, "byteLength": 96, "byteStride": 24},
                {"buffer": 0, "byteOffset": )" +
            num(idx) + R"(, "byteLength": )" + num(4 + 6 * size) + "}]";
        writeGlb(dir / "quad.glb", body, bin);
        const TriangleMesh m = mesh::loadGltf(dir / "quad.glb");
        ASSERT_EQ(m.indices.size(), 6u) << type;
        for (std::size_t i = 0; i < 6; ++i)
            expectNear(m.positions[m.indices[i]], quad[order[i]], "type " + std::to_string(type));
        for (const glm::vec3& n : m.normals)
            expectNear(n, {0, 0, 1}, "normal");
    }
}

TEST(Gltf, ColorIsBaseColorFactorTimesColor0) {
    TempDir dir;
    Bin bin;
    const std::size_t pos = bin.add(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
    const std::size_t u8 =
        bin.add(std::vector<std::uint8_t>{255, 128, 0, 255, 0, 255, 51, 102, 255, 255, 255, 0});
    const std::size_t u16 =
        bin.add(std::vector<std::uint16_t>{65535, 0, 32768, 0, 65535, 0, 0, 0, 65535});
    const std::size_t f32 =
        bin.add(std::vector<float>{0.5f, 0.5f, 0.5f, 0.5f, 1, 0, 0, 1, 0, 0, 1, 0.25f});
    const std::string body =
        R"("materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.5, 1.0, 0.25, 0.8]}}],
          "meshes": [{"primitives": [
            {"attributes": {"POSITION": 0, "COLOR_0": 1}, "material": 0},
            {"attributes": {"POSITION": 0, "COLOR_0": 2}, "material": 0},
            {"attributes": {"POSITION": 0, "COLOR_0": 3}},
            {"attributes": {"POSITION": 0}}]}],
          "nodes": [{"mesh": 0}],
          "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
            {"bufferView": 1, "componentType": 5121, "normalized": true, "count": 3, "type": "VEC4"},
            {"bufferView": 2, "componentType": 5123, "normalized": true, "count": 3, "type": "VEC3"},
            {"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC4"}],
          "bufferViews": [{"buffer": 0, "byteOffset": )" +
        num(pos) + R"(, "byteLength": 36}, {"buffer": 0, "byteOffset": )" + num(u8) +
        R"(, "byteLength": 12}, {"buffer": 0, "byteOffset": )" + num(u16) +
        R"(, "byteLength": 18}, {"buffer": 0, "byteOffset": )" + num(f32) +
        R"(, "byteLength": 48}])";
    writeGltf(dir / "colors.gltf", body, bin); // no scenes: the root nodes are drawn
    const TriangleMesh m = mesh::loadGltf(dir / "colors.gltf");
    ASSERT_EQ(m.colors.size(), 12u); // flat normals: 3 own vertices per triangle
    const glm::vec4 f(0.5f, 1.0f, 0.25f, 0.8f);
    const std::vector<glm::vec4> want = {f * glm::vec4(1, 128 / 255.0f, 0, 1),
                                         f * glm::vec4(0, 1, 0.2f, 0.4f),
                                         f * glm::vec4(1, 1, 1, 0),
                                         f * glm::vec4(1, 0, 32768 / 65535.0f, 1),
                                         f * glm::vec4(0, 1, 0, 1),
                                         f * glm::vec4(0, 0, 1, 1),
                                         {0.5f, 0.5f, 0.5f, 0.5f},
                                         {1, 0, 0, 1},
                                         {0, 0, 1, 0.25f},
                                         glm::vec4(1),
                                         glm::vec4(1),
                                         glm::vec4(1)};
    for (std::size_t i = 0; i < 12; ++i) {
        const glm::vec4 got = m.colors[m.indices[i]];
        for (int c = 0; c < 4; ++c)
            EXPECT_NEAR(got[c], want[i][c], 1e-6f) << "corner " << i << " channel " << c;
    }
}

// A cube with 8 shared corners and no NORMAL: glTF asks for flat normals.
TEST(Gltf, MissingNormalsGiveFlatOutwardNormals) {
    TempDir dir;
    Bin bin;
    std::vector<float> corners8;
    for (int i = 0; i < 8; ++i)
        corners8.insert(corners8.end(), {float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1)});
    const std::size_t pos = bin.add(corners8);
    // Counter-clockwise seen from outside.
    const std::size_t idx =
        bin.add(std::vector<std::uint16_t>{0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                           2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5});
    const std::string body =
        R"("nodes": [{"mesh": 0, "translation": [5, 0, 0]}], "scenes": [{"nodes": [0]}],
          "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
          "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3"},
            {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}],
          "bufferViews": [{"buffer": 0, "byteOffset": )" +
        num(pos) + R"(, "byteLength": 96}, {"buffer": 0, "byteOffset": )" + num(idx) +
        R"(, "byteLength": 72}])";
    writeGltf(dir / "cube.gltf", body, bin);
    const TriangleMesh m = mesh::loadGltf(dir / "cube.gltf");
    ASSERT_EQ(m.triangleCount(), 12u);
    const glm::vec3 centre(5.5f, 0.5f, 0.5f);
    for (std::size_t t = 0; t < 12; ++t) {
        const std::vector<glm::vec3> c = corners(m, t);
        const glm::vec3 mid = (c[0] + c[1] + c[2]) / 3.0f;
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 n = m.normals[m.indices[3 * t + k]];
            EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f);
            EXPECT_GT(glm::dot(n, mid - centre), 0.1f) << "triangle " << t;
            expectNear(n, geometricNormal(m, t), "flat normal of triangle " + num(t));
        }
    }
    expectNear(m.lo, {5, 0, 0}, "lo");
    expectNear(m.hi, {6, 1, 1}, "hi");
}

// Strips and fans are triangles too: a quad each, both facing +z.
TEST(Gltf, StripsAndFansBecomeTriangleLists) {
    TempDir dir;
    Bin bin;
    const std::size_t strip = bin.add(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});
    const std::size_t fan = bin.add(std::vector<float>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
    const std::string body =
        R"("nodes": [{"mesh": 0}],
          "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "mode": 5},
                                     {"attributes": {"POSITION": 1}, "mode": 6},
                                     {"attributes": {"POSITION": 1}, "mode": 1}]}],
          "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
                        {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"}],
          "bufferViews": [{"buffer": 0, "byteOffset": )" +
        num(strip) + R"(, "byteLength": 48}, {"buffer": 0, "byteOffset": )" + num(fan) +
        R"(, "byteLength": 48}])";
    writeGltf(dir / "strip.gltf", body, bin);
    const TriangleMesh m = mesh::loadGltf(dir / "strip.gltf");
    ASSERT_EQ(m.triangleCount(), 4u); // the LINES primitive is skipped
    for (std::size_t t = 0; t < 4; ++t)
        expectNear(geometricNormal(m, t), {0, 0, 1}, "triangle " + num(t));
}

// The committed example tools: metres, tip at the origin, handle along +z,
// closed and wound counter-clockwise from outside.
TEST(Gltf, ToolModelsLoad) {
    const std::filesystem::path folder =
        std::filesystem::path(CUTAWAY_SOURCE_DIR) / "scenes/meshes";
    const std::pair<const char*, glm::vec4> tools[] = {
        {"retractor.glb", {0.75f, 0.77f, 0.8f, 1.0f}}, {"forceps.gltf", {0.8f, 0.8f, 0.82f, 1.0f}}};
    for (const auto& [name, color] : tools) {
        SCOPED_TRACE(name);
        const TriangleMesh m = mesh::loadGltf(folder / name);
        EXPECT_GT(m.triangleCount(), 20u);
        const glm::vec3 extent = m.hi - m.lo;
        const float longest = std::max({extent.x, extent.y, extent.z});
        EXPECT_EQ(longest, extent.z); // the handle runs along +z
        EXPECT_GE(longest, 0.08f);
        EXPECT_LE(longest, 0.2f);
        EXPECT_NEAR(m.lo.z, 0.0f, 0.002f); // the tip is at the origin
        EXPECT_TRUE(glm::all(glm::lessThanEqual(m.lo, glm::vec3(0.002f))));
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(m.hi, glm::vec3(-0.002f))));
        for (const glm::vec3& n : m.normals)
            ASSERT_NEAR(glm::length(n), 1.0f, 1e-5f);
        for (const glm::vec4& c : m.colors)
            ASSERT_EQ(c, color);
        double volume = 0.0;
        for (std::size_t t = 0; t < m.triangleCount(); ++t) {
            const std::vector<glm::vec3> c = corners(m, t);
            volume += glm::dot(c[0], glm::cross(c[1], c[2])) / 6.0;
            // Flat-shaded: each corner's normal is its triangle's.
            for (int k = 0; k < 3; ++k)
                ASSERT_GT(glm::dot(geometricNormal(m, t), m.normals[m.indices[3 * t + k]]), 0.99f);
        }
        // Counter-clockwise from outside gives a positive volume (of blocks
        // that overlap a little, so only roughly a tool's: 0.5 to 20 cm^3).
        EXPECT_GT(volume, 0.5e-6);
        EXPECT_LT(volume, 20e-6);
        EXPECT_TRUE(closedAndConsistent(m, 1e-6f));
    }
}

} // namespace
} // namespace cutaway::test

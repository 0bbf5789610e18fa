// The mesh pass (render/mesh_pass.hpp): opaque meshes are depth-tested with
// the volume's slices and composited exactly like an opaque layer at their
// depth. Each test compares renders of one scene with and without parts, so a
// pass that ignored depth, drew in the wrong order or misplaced a mesh fails.
#include "../io/temp_dir.hpp"
#include "gpu_fixture.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <string>
#include <vector>

namespace cutaway::test {
namespace {

std::string base64(const std::vector<std::uint8_t>& bytes) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::uint32_t n = (std::uint32_t(bytes[i]) << 16) |
                                (i + 1 < bytes.size() ? std::uint32_t(bytes[i + 1]) << 8 : 0u) |
                                (i + 2 < bytes.size() ? std::uint32_t(bytes[i + 2]) : 0u);
        out += table[(n >> 18) & 63];
        out += table[(n >> 12) & 63];
        out += i + 1 < bytes.size() ? table[(n >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? table[n & 63] : '=';
    }
    return out;
}

// A cube [-1, 1]^3 (model units) with flat normals and a base colour, as .gltf.
std::filesystem::path writeCube(const std::filesystem::path& file) {
    std::vector<float> positions, normals;
    std::vector<std::uint16_t> indices;
    for (int axis = 0; axis < 3; ++axis) {
        for (int sign = -1; sign <= 1; sign += 2) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            const auto base = static_cast<std::uint16_t>(positions.size() / 3);
            for (int corner = 0; corner < 4; ++corner) {
                float p[3], n[3] = {0, 0, 0};
                p[axis] = float(sign);
                p[u] = (corner == 1 || corner == 2) ? 1.0f : -1.0f;
                p[v] = corner >= 2 ? 1.0f : -1.0f;
                n[axis] = float(sign);
                positions.insert(positions.end(), p, p + 3);
                normals.insert(normals.end(), n, n + 3);
            }
            for (int k : {0, 1, 2, 0, 2, 3})
                indices.push_back(static_cast<std::uint16_t>(base + k));
        }
    }
    std::vector<std::uint8_t> buffer(positions.size() * 4 * 2 + indices.size() * 2);
    std::memcpy(buffer.data(), positions.data(), positions.size() * 4);
    std::memcpy(buffer.data() + positions.size() * 4, normals.data(), normals.size() * 4);
    std::memcpy(buffer.data() + positions.size() * 8, indices.data(), indices.size() * 2);
    const std::size_t pBytes = positions.size() * 4, iBytes = indices.size() * 2;
    std::ofstream out(file);
    out << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
        << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1},"indices":2,"material":0}]}],)"
        << R"("materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.2,0.6,0.9,1]}}],)"
        << R"("buffers":[{"byteLength":)" << buffer.size()
        << R"(,"uri":"data:application/octet-stream;base64,)" << base64(buffer) << R"("}],)"
        << R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":)" << pBytes << "},"
        << R"({"buffer":0,"byteOffset":)" << pBytes << R"(,"byteLength":)" << pBytes << "},"
        << R"({"buffer":0,"byteOffset":)" << 2 * pBytes << R"(,"byteLength":)" << iBytes << "}],"
        << R"("accessors":[{"bufferView":0,"componentType":5126,"count":24,"type":"VEC3","min":[-1,-1,-1],"max":[1,1,1]},)"
        << R"({"bufferView":1,"componentType":5126,"count":24,"type":"VEC3"},)"
        << R"({"bufferView":2,"componentType":5123,"count":36,"type":"SCALAR"}]})";
    return file;
}

glm::vec4 px4(const Image& image, int x, int y) {
    const float* p = image.pixel(x, y);
    return {p[0], p[1], p[2], p[3]};
}

// A cube of half-size `half` mm at `centre` (world), in the scene's units.
MeshSpec cube(const std::filesystem::path& file, glm::dvec3 centre, double half) {
    MeshSpec m;
    m.file = file;
    m.placement = glm::scale(glm::translate(glm::dmat4(1.0), centre), glm::dvec3(half));
    return m;
}

class MeshRenderTest : public GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
        m_file = writeCube(m_dir / "cube.gltf");
        m_scene = headScene(48, 48, 48); // front view: the eye is at -y, looking along +y
        m_scene.camera.projection = Projection::Orthographic;
        m_scene.camera.orthoHeight = 48.0; // 1 mm per pixel, the view centred on the volume
    }
    // The same scene with a volume no sample of which is visible.
    Scene withoutVolume(Scene s) const {
        for (TransferPoint& p : s.transfer.points)
            p.alpha = 0.0f;
        return s;
    }
    TempDir m_dir;
    std::filesystem::path m_file;
    Scene m_scene;
};

TEST_F(MeshRenderTest, AMeshInFrontHidesTheVolumeAndOneBehindShowsThroughIt) {
    const Image volumeOnly = renderScene(ctx(), m_scene);
    for (const double y : {-40.0, 40.0}) { // in front of the volume box [-24, 24]^3, behind it
        SCOPED_TRACE(y < 0 ? "in front" : "behind");
        Scene s = m_scene;
        s.meshes.push_back(cube(m_file, {0.0, y, 0.0}, 8.0));
        const Image both = renderScene(ctx(), s);
        const Image meshOnly = renderScene(ctx(), withoutVolume(s));
        int covered = 0;
        float worst = 0.0f;
        for (int py = 0; py < both.height; ++py) {
            for (int px = 0; px < both.width; ++px) {
                const glm::vec4 v = px4(volumeOnly, px, py), m = px4(meshOnly, px, py);
                const glm::vec4 b = px4(both, px, py);
                // The mesh is opaque where it covers a pixel and absent elsewhere.
                ASSERT_TRUE(m.w == 0.0f || m.w == 1.0f) << px << "," << py << ": " << m.w;
                if (m.w == 1.0f) ++covered;
                // In front: the mesh alone. Behind: the volume over the mesh.
                const glm::vec4 expected = m.w == 0.0f ? v : y < 0 ? m : v + (1.0f - v.w) * m;
                for (int c = 0; c < 4; ++c)
                    worst = std::max(worst, std::abs(b[c] - expected[c]));
            }
        }
        EXPECT_LT(worst, 2e-3f);
        // A 16 mm cube in a 48 mm wide view of 48 pixels covers about 16 x 16 pixels.
        EXPECT_GT(covered, 12 * 12);
        EXPECT_LT(covered, 20 * 20);
        // The tissue in the middle of the head covers the mesh behind it.
        if (y > 0) {
            EXPECT_GT(std::abs(both.pixel(24, 24)[0] - meshOnly.pixel(24, 24)[0]), 0.05f);
        }
    }
}

TEST_F(MeshRenderTest, TheDepthChannelIsTheMeshsWhereTheMeshIsNearer) {
    // The eye 200 mm in front of the volume's centre: a cube's face at y = f
    // lies at Z = 200 + f (orthographic: along the view, from the eye's plane).
    m_scene.camera.useOrbit = false;
    m_scene.camera.eye = glm::dvec3(0.0, -200.0, 0.0);
    m_scene.output.depth = true;
    const Image volumeOnly = renderScene(ctx(), m_scene);
    for (const double y : {-40.0, 40.0}) { // in front of the volume box [-24, 24]^3, behind it
        SCOPED_TRACE(y < 0 ? "in front" : "behind");
        Scene s = m_scene;
        s.meshes.push_back(cube(m_file, {0.0, y, 0.0}, 8.0));
        const Image both = renderScene(ctx(), s);
        const Image meshOnly = renderScene(ctx(), withoutVolume(s));
        const float face = float(200.0 + y - 8.0);
        int meshWins = 0, volumeWins = 0;
        for (std::size_t p = 0; p < both.depth.size(); ++p) {
            const bool mesh = meshOnly.rgba[4 * p + 3] == 1.0f;
            const float v = volumeOnly.depth[p];
            EXPECT_EQ(meshOnly.depth[p], mesh ? face : INFINITY) << p;
            const float expected = mesh ? std::min(face, v) : v;
            if (std::isinf(expected))
                EXPECT_EQ(both.depth[p], expected) << p;
            else
                EXPECT_NEAR(both.depth[p], expected, 1e-3f) << p;
            meshWins += mesh && face < v;
            volumeWins += mesh && v < face;
        }
        // Control: in front, the mesh is nearer wherever it is; behind, the
        // head is nearer in the middle of it.
        EXPECT_GT(y < 0 ? meshWins : volumeWins, 12 * 12);
        EXPECT_EQ(y < 0 ? volumeWins : 0, 0);
    }
}

TEST_F(MeshRenderTest, AMeshInsideTheVolumeHidesOnlyWhatLiesBehindItsSurface) {
    // A cube inside the head: the volume in front of its face stays; compared
    // with the cube behind the volume, the picture must differ (less tissue in front).
    Scene inside = m_scene, behind = m_scene;
    for (Scene* s : {&inside, &behind}) // faint tissue, so that depth matters all the way through
        for (TransferPoint& p : s->transfer.points)
            p.alpha *= 0.1f;
    inside.meshes.push_back(cube(m_file, {0.0, 0.0, 0.0}, 6.0));
    behind.meshes.push_back(cube(m_file, {0.0, 40.0, 0.0}, 6.0));
    const Image a = renderScene(ctx(), inside), b = renderScene(ctx(), behind);
    const Image meshOnly = renderScene(ctx(), withoutVolume(inside));
    // Opaque where the cube is, with the tissue in front of it composited over
    // it: not the bare cube, and not the whole head's depth of tissue either.
    EXPECT_FLOAT_EQ(a.pixel(24, 24)[3], 1.0f);
    EXPECT_GT(std::abs(a.pixel(24, 24)[0] - meshOnly.pixel(24, 24)[0]), 1e-3f);
    EXPECT_GT(std::abs(a.pixel(24, 24)[0] - b.pixel(24, 24)[0]), 1e-3f);
}

TEST_F(MeshRenderTest, AnAttachedMeshMovesWithItsOperator) {
    OperatorSpec op;
    op.type = OperatorType::Retractor;
    op.params.kind.x = CW_OP_RETRACTOR;
    op.params.a = glm::vec4(0.6f, 0.5f, 0.0f, 0.0f); // no opening: the volume is unchanged
    op.localToWorld =
        glm::scale(glm::translate(glm::dmat4(1.0), glm::dvec3(10.0, 0.0, 5.0)), glm::dvec3(8.0));
    Scene attached = m_scene, world = m_scene;
    attached.operators = {op};
    world.operators = {op};
    MeshSpec m = cube(m_file, {0.0, -30.0, 0.0}, 4.0);
    m.attach = 0;
    attached.meshes.push_back(m);
    world.meshes.push_back(cube(m_file, {10.0, -30.0, 5.0}, 4.0));
    const ImageDiff d = compareImages(renderScene(ctx(), attached), renderScene(ctx(), world));
    EXPECT_LT(d.maxAbs, 1e-5f);
    // And the colour override replaces the model's base colour.
    attached.meshes[0].color = glm::vec3(1.0f, 0.0f, 0.0f);
    const Image red = renderScene(ctx(), withoutVolume(attached));
    bool sawRed = false;
    for (int py = 0; py < red.height; ++py)
        for (int px = 0; px < red.width; ++px) {
            const glm::vec4 p = px4(red, px, py);
            if (p.w == 1.0f) { // red, plus the lights' white highlight
                sawRed = true;
                EXPECT_EQ(p[1], p[2]);
                EXPECT_GT(p[0], p[1] + 0.1f);
            }
        }
    EXPECT_TRUE(sawRed);
}

TEST_F(MeshRenderTest, AGlyphOutlinesTheOperatorBox) {
    OperatorSpec op;
    op.type = OperatorType::Dilator;
    op.params.kind.x = CW_OP_DILATOR;
    op.params.a = glm::vec4(0.3f, 1.0f, 0.0f, 0.0f); // magnification 1: the volume is unchanged
    op.localToWorld = glm::scale(glm::dmat4(1.0), glm::dvec3(12.0));
    Scene s = withoutVolume(m_scene);
    s.operators = {op};
    const Image none = renderScene(ctx(), s);
    s.operators[0].glyph.enabled = true;
    s.operators[0].glyph.width = 1.5;
    const Image glyph = renderScene(ctx(), s);
    // Ortho front view: the box's front face spans x, z in [-12, 12] mm, 1 px per mm,
    // centred at pixel 24. Its edges are drawn, its middle is empty.
    EXPECT_EQ(none.pixel(12, 24)[3], 0.0f);
    EXPECT_FLOAT_EQ(glyph.pixel(12, 24)[3], 1.0f); // left edge, x = -12
    EXPECT_FLOAT_EQ(glyph.pixel(35, 24)[3], 1.0f); // right edge, x = +12
    EXPECT_FLOAT_EQ(glyph.pixel(24, 12)[3], 1.0f); // top edge
    EXPECT_EQ(glyph.pixel(24, 24)[3], 0.0f);       // the middle
    EXPECT_EQ(glyph.pixel(4, 4)[3], 0.0f);         // outside
}

TEST_F(MeshRenderTest, TheRayCasterStopsAtTheMeshesAsTheSlicesDo) {
    // In front of the volume, inside it (faint tissue, so depth matters all
    // the way through) and behind it, with an operator: the rays end at the
    // meshes' depth where the slices fail the depth test, and the image goes
    // over the meshes' alike. The same but for rounding at the cube's edges.
    Scene faint = m_scene;
    for (TransferPoint& p : faint.transfer.points)
        p.alpha *= 0.1f;
    OperatorSpec op;
    op.type = OperatorType::Dilator;
    op.params.kind.x = CW_OP_DILATOR;
    op.params.a = glm::vec4(0.3f, 1.5f, 0.0f, 0.0f);
    op.localToWorld =
        glm::scale(glm::translate(glm::dmat4(1.0), glm::dvec3(-12.0, 0.0, 8.0)), glm::dvec3(10.0));
    for (const double y : {-40.0, 0.0, 40.0}) {
        SCOPED_TRACE(y);
        Scene s = faint;
        s.meshes.push_back(cube(m_file, {4.0, y, 0.0}, 8.0));
        s.operators = {op};
        const Image sliced = renderScene(ctx(), s);
        s.render.method = RenderMethod::Raycast;
        const Image cast = renderScene(ctx(), s);
        int differing = 0;
        for (std::size_t i = 0; i < cast.rgba.size(); i += 4) {
            float e = 0.0f;
            for (std::size_t c = 0; c < 4; ++c)
                e = std::max(e, std::abs(cast.rgba[i + c] - sliced.rgba[i + c]));
            differing += e > 2e-3f;
        }
        // Measured: none; without the depth ending the rays, 256 where the
        // cube hides the volume.
        EXPECT_LE(differing, 8) << "of 48 x 48";
        EXPECT_LT(compareImages(sliced, cast).meanAbs, 1e-3);
        // The cube is there to hide something: it covers the middle.
        EXPECT_FLOAT_EQ(renderScene(ctx(), withoutVolume(s)).pixel(26, 24)[3], 1.0f);
    }
}

} // namespace
} // namespace cutaway::test

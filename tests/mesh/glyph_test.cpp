// boxOutline: 12 square bars along a box's edges, flat-shaded and closed;
// TriangleMesh::append.
#include "gltf_writer.hpp"

namespace cutaway::test {
namespace {

using mesh::TriangleMesh;

const glm::vec3 kLo(-1.0f, 2.0f, 0.5f), kHi(3.0f, 2.5f, 4.0f);
constexpr float kWidth = 0.2f;
const glm::vec4 kColor(0.9f, 0.3f, 0.1f, 0.75f);

TEST(Glyph, BoxOutlineCountsAndBounds) {
    const TriangleMesh m = mesh::boxOutline(kLo, kHi, kWidth, kColor);
    EXPECT_EQ(m.triangleCount(), 12u * 6u * 2u);
    EXPECT_EQ(m.positions.size(), 12u * 6u * 4u);
    EXPECT_EQ(m.normals.size(), m.positions.size());
    ASSERT_EQ(m.colors.size(), m.positions.size());
    for (const glm::vec4& c : m.colors)
        EXPECT_EQ(c, kColor);
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (const glm::vec3& p : m.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    for (int a = 0; a < 3; ++a) {
        EXPECT_FLOAT_EQ(m.lo[a], kLo[a] - kWidth / 2) << a;
        EXPECT_FLOAT_EQ(m.hi[a], kHi[a] + kWidth / 2) << a;
        EXPECT_FLOAT_EQ(lo[a], m.lo[a]) << a;
        EXPECT_FLOAT_EQ(hi[a], m.hi[a]) << a;
    }
    for (std::uint32_t i : m.indices)
        ASSERT_LT(i, m.positions.size());
}

// Each bar is 24 vertices: w x w across, the edge's length plus w along it,
// centred on one of the box's 12 edges, each edge once.
TEST(Glyph, BarsFollowTheEdges) {
    const TriangleMesh m = mesh::boxOutline(kLo, kHi, kWidth, kColor);
    std::vector<int> edgesSeen(12, 0);
    for (std::size_t bar = 0; bar < 12; ++bar) {
        glm::vec3 lo(1e9f), hi(-1e9f);
        for (std::size_t v = 24 * bar; v < 24 * bar + 24; ++v) {
            lo = glm::min(lo, m.positions[v]);
            hi = glm::max(hi, m.positions[v]);
        }
        const glm::vec3 size = hi - lo, centre = 0.5f * (lo + hi);
        int along = -1;
        for (int a = 0; a < 3; ++a) {
            if (std::abs(size[a] - kWidth) > 1e-5f) {
                ASSERT_EQ(along, -1) << "bar " << bar << " is long in two axes";
                along = a;
            }
        }
        ASSERT_NE(along, -1);
        EXPECT_NEAR(size[along], kHi[along] - kLo[along] + kWidth, 1e-5f);
        EXPECT_NEAR(centre[along], 0.5f * (kLo[along] + kHi[along]), 1e-5f);
        int corner = 0, bit = 0;
        for (int a = 0; a < 3; ++a) {
            if (a == along) continue;
            const bool high = std::abs(centre[a] - kHi[a]) < 1e-5f;
            EXPECT_TRUE(high || std::abs(centre[a] - kLo[a]) < 1e-5f) << "bar " << bar;
            corner |= (high ? 1 : 0) << bit++;
        }
        ++edgesSeen[along * 4 + corner];
    }
    for (int e = 0; e < 12; ++e)
        EXPECT_EQ(edgesSeen[e], 1) << "edge " << e;
}

TEST(Glyph, FacesPointOutwardAndWindCounterClockwise) {
    const TriangleMesh m = mesh::boxOutline(kLo, kHi, kWidth, kColor);
    for (std::size_t t = 0; t < m.triangleCount(); ++t) {
        const std::size_t bar = m.indices[3 * t] / 24;
        glm::vec3 centre(0.0f);
        for (std::size_t v = 24 * bar; v < 24 * bar + 24; ++v)
            centre += m.positions[v] / 24.0f;
        const std::vector<glm::vec3> c = corners(m, t);
        const glm::vec3 mid = (c[0] + c[1] + c[2]) / 3.0f;
        const glm::vec3 winding = glm::cross(c[1] - c[0], c[2] - c[0]);
        ASSERT_GT(glm::length(winding), 1e-6f) << "degenerate triangle " << t;
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 n = m.normals[m.indices[3 * t + k]];
            ASSERT_NEAR(glm::length(n), 1.0f, 1e-6f);
            // Axis-aligned and pointing away from the bar's centre.
            ASSERT_NEAR(std::abs(n.x) + std::abs(n.y) + std::abs(n.z), 1.0f, 1e-6f);
            ASSERT_GT(glm::dot(n, mid - centre), 0.0f) << "triangle " << t;
            ASSERT_GT(glm::dot(glm::normalize(winding), n), 0.999f) << "triangle " << t;
        }
    }
    EXPECT_TRUE(closedAndConsistent(m, 1e-5f));
}

TEST(Glyph, SwappedCornersGiveTheSameOutline) {
    const TriangleMesh a = mesh::boxOutline(kLo, kHi, kWidth, kColor);
    const TriangleMesh b = mesh::boxOutline(kHi, kLo, kWidth, kColor);
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.indices, b.indices);
}

TEST(Mesh, AppendOffsetsIndicesAndGrowsBounds) {
    const TriangleMesh a = mesh::boxOutline({0, 0, 0}, {1, 1, 1}, 0.1f, kColor);
    const TriangleMesh b = mesh::boxOutline({5, -2, 0}, {6, 1, 1}, 0.1f, glm::vec4(1.0f));
    TriangleMesh sum;
    sum.append(a);
    // Appending to an empty mesh takes the other's bounds (not the origin's).
    EXPECT_EQ(sum.lo, a.lo);
    EXPECT_EQ(sum.hi, a.hi);
    sum.append(b);
    ASSERT_EQ(sum.positions.size(), a.positions.size() + b.positions.size());
    ASSERT_EQ(sum.indices.size(), a.indices.size() + b.indices.size());
    for (std::size_t i = 0; i < b.indices.size(); ++i) {
        const std::uint32_t j = sum.indices[a.indices.size() + i];
        ASSERT_EQ(sum.positions[j], b.positions[b.indices[i]]);
        ASSERT_EQ(sum.colors[j], glm::vec4(1.0f));
    }
    EXPECT_EQ(sum.lo, glm::min(a.lo, b.lo));
    EXPECT_EQ(sum.hi, glm::max(a.hi, b.hi));
    sum.append(TriangleMesh{}); // nothing to add: bounds unchanged
    EXPECT_EQ(sum.lo, glm::min(a.lo, b.lo));

    TriangleMesh twice = a;
    twice.append(twice);
    ASSERT_EQ(twice.indices.size(), 2 * a.indices.size());
    EXPECT_EQ(twice.indices[a.indices.size()], a.indices[0] + a.positions.size());
    EXPECT_EQ(twice.lo, a.lo);
}

} // namespace
} // namespace cutaway::test

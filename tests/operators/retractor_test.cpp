// Retractor (a split): round trip, the opening is empty and filled with the
// incision plane, fixed faces, the analytic Jacobian, and a signed distance
// with unit gradient at the opening's walls.
#include "operator_test_util.hpp"

#include <vector>

namespace cutaway::test {
namespace {

struct RetractorCase {
    const char* name;
    OperatorParams o;
    // The signed distance is first order, exact on the wall: tested within
    // `band` of it, where its gradient is within `gradientTolerance` of the
    // wall's unit normal (and its value within band * gradientTolerance).
    float band;
    float gradientTolerance;
};

std::vector<RetractorCase> retractorCases() {
    return {
        {"typical", retractorParams(0.6f, 0.8f, 0.3f), 0.01f, 0.01f},
        // The whole box: incision from y = -1 to 1 and down to z = -1, spread to 0.95.
        {"extreme", retractorParams(1.0f, 2.0f, 0.95f), 0.01f, 0.02f},
        // Short and shallow but wide open: steep walls (|grad w| up to ~8) curved
        // with radii down to L^2 / (4 W) = 0.005, so first order holds only very near.
        {"narrow", retractorParams(0.1f, 0.2f, 0.5f), 5e-4f, 0.05f},
    };
}

// Half opening w(y, z) and its gradient.
glm::vec3 opening(glm::vec3 q, const OperatorParams& o) {
    return shader::retractorOpening(q.y, q.z, o);
}

// A point of the incision's footprint where the opening is at least `minWidth`.
glm::vec3 inOpeningFootprint(Rng& rng, const OperatorParams& o, float minWidth) {
    for (;;) {
        const glm::vec3 q(0.0f, rng.uniform(-o.a.x, o.a.x), rng.uniform(1.0f - o.a.y, 1.0f));
        if (opening(q, o).x > minWidth) return q;
    }
}

} // namespace

TEST(Retractor, BackwardUndoesForward) {
    for (const RetractorCase& c : retractorCases()) {
        SCOPED_TRACE(c.name);
        Rng rng(21);
        float worst = 0.0f;
        for (int i = 0; i < 10000; ++i) {
            // Even i: anywhere; odd i: beside the incision, where the spread is.
            glm::vec3 p = rng.inUnitBox();
            if (i % 2) p = inOpeningFootprint(rng, c.o, 0.0f) + glm::vec3(p.x, 0.0f, 0.0f);
            if (std::abs(p.x) < 1e-6f) continue; // on the incision itself
            const glm::vec3 q = shader::operatorForward(p, c.o);
            EXPECT_GE(std::abs(q.x), opening(q, c.o).x) << "material moved into the opening";
            const glm::vec4 back = shader::operatorBackward(q, c.o);
            worst = std::max(worst, maxAbs(glm::vec3(back) - p));
            EXPECT_GT(back.w, 0.0f);
        }
        EXPECT_LE(worst, 1e-5f);
        recordWorst(c.name, worst);
    }
}

TEST(Retractor, TheOpeningIsEmptyAndFilledWithTheIncisionPlane) {
    for (const RetractorCase& c : retractorCases()) {
        SCOPED_TRACE(c.name);
        Rng rng(22);
        for (int i = 0; i < 10000; ++i) {
            glm::vec3 q = inOpeningFootprint(rng, c.o, 1e-3f);
            q.x = rng.uniform(-0.999f, 0.999f) * opening(q, c.o).x;
            const glm::vec4 back = shader::operatorBackward(q, c.o);
            EXPECT_LE(back.w, 0.0f) << "q " << q.x << " " << q.y << " " << q.z;
            EXPECT_EQ(glm::vec3(back), glm::vec3(0.0f, q.y, q.z));
        }
        // Anywhere in the box: empty exactly where |x'| < w(y, z).
        for (int i = 0; i < 10000; ++i) {
            const glm::vec3 q = rng.inUnitBox();
            const float w = opening(q, c.o).x;
            if (std::abs(std::abs(q.x) - w) < 1e-6f) continue;
            EXPECT_EQ(signedDistance(q, c.o) <= 0.0f, std::abs(q.x) < w);
        }
    }
}

TEST(Retractor, ZeroOpeningIsExactlyTheIdentity) {
    const OperatorParams o = retractorParams(0.6f, 0.8f, 0.0f);
    Rng rng(23);
    for (int i = 0; i < 10000; ++i) {
        const glm::vec3 q = rng.inBox(glm::vec3(-1.5f), glm::vec3(1.5f));
        EXPECT_EQ(shader::operatorForward(q, o), q);
        EXPECT_EQ(shader::operatorBackward(q, o), glm::vec4(q, CW_NO_CUT));
        EXPECT_EQ(shader::operatorJacobian(q, o), glm::mat3(1.0f));
    }
}

TEST(Retractor, BoxFacesStayFixed) {
    for (const RetractorCase& c : retractorCases()) {
        SCOPED_TRACE(c.name);
        Rng rng(24);
        // |x| = 1 always; |y| = 1 since L <= 1; z = -1 since D <= 2.
        const std::pair<int, float> faces[] = {
            {0, -1.0f}, {0, 1.0f}, {1, -1.0f}, {1, 1.0f}, {2, -1.0f}};
        for (const auto& [axis, side] : faces)
            for (int i = 0; i < 2000; ++i) {
                const glm::vec3 q = onFace(rng, axis, side);
                const glm::vec4 back = shader::operatorBackward(q, c.o);
                EXPECT_LE(maxAbs(glm::vec3(back) - q), 1e-6f);
                EXPECT_GE(back.w, 0.0f);
                EXPECT_LE(maxAbs(shader::operatorForward(q, c.o) - q), 1e-6f);
            }
    }
}

TEST(Retractor, JacobianMatchesFiniteDifferences) {
    const float h = 3e-4f; // extrapolated: the narrow case's walls are sharply curved
    for (const RetractorCase& c : retractorCases()) {
        SCOPED_TRACE(c.name);
        Rng rng(25);
        float worst = 0.0f;
        int beside = 0;
        for (int i = 0; i < 10000; ++i) {
            glm::vec3 q = rng.inBox(glm::vec3(-0.99f), glm::vec3(0.99f));
            if (i % 2) q = inOpeningFootprint(rng, c.o, 0.0f) + glm::vec3(q.x, 0.0f, 0.0f);
            // The map is only C0 at the walls (x = 0 is filled in the opening)
            // and at |x'| = 1 (identity beyond the box).
            if (std::abs(signedDistance(q, c.o)) < 0.02f || std::abs(q.x) > 0.99f) continue;
            // w(y, z) is C1, not C2, at the incision's ends, bottom and surface:
            // differences straddling them are only first-order accurate.
            if (std::abs(std::abs(q.y) - c.o.a.x) < 2.0f * h ||
                std::abs(q.z - (1.0f - c.o.a.y)) < 2.0f * h || std::abs(q.z - 1.0f) < 2.0f * h)
                continue;
            beside += std::abs(q.x) > opening(q, c.o).x && opening(q, c.o).x > 0.0f ? 1 : 0;
            const glm::mat3 analytic = shader::operatorJacobian(q, c.o);
            const float err = jacobianError(analytic, extrapolatedJacobian(q, c.o, h));
            worst = std::max(worst, err);
            EXPECT_LE(err, 2e-3f) << "q " << q.x << " " << q.y << " " << q.z;
        }
        EXPECT_GT(beside, 2000);
        recordWorst(c.name, worst);
    }
}

// The renderer's band |w| < D and cut normal grad w must be in real units.
TEST(Retractor, SignedDistanceHasUnitGradientAtTheWalls) {
    const float h = 1e-4f;
    for (const RetractorCase& c : retractorCases()) {
        SCOPED_TRACE(c.name);
        Rng rng(26);
        float worst = 0.0f;
        for (int i = 0; i < 5000; ++i) {
            glm::vec3 q = inOpeningFootprint(rng, c.o, 0.05f);
            const glm::vec3 w = opening(q, c.o);
            const float side = rng.uniform(0.0f, 1.0f) < 0.5f ? -1.0f : 1.0f;
            const float offset = rng.uniform(-c.band, c.band); // > 0: material, < 0: opening
            const glm::vec3 normal = glm::normalize(glm::vec3(side, -w.y, -w.z));
            q = glm::vec3(side * w.x, q.y, q.z) + offset * normal;
            if (q.z > 1.0f - h || std::abs(q.y) > 0.95f * c.o.a.x) continue;
            EXPECT_NEAR(signedDistance(q, c.o), offset, c.band * c.gradientTolerance);
            const glm::vec3 g = finiteDifferenceGradient(q, c.o, h);
            const float err = maxAbs(g - normal);
            worst = std::max(worst, err);
            EXPECT_LE(err, c.gradientTolerance)
                << "q " << q.x << " " << q.y << " " << q.z << " |grad w| " << glm::length(g);
        }
        // Beyond the incision's ends and bottom: the distance to its edge.
        for (int i = 0; i < 2000 && c.o.a.x < 0.9f; ++i) {
            const glm::vec3 q(rng.uniform(-0.3f, 0.3f), rng.uniform(c.o.a.x + 0.01f, 1.0f),
                              rng.uniform(-1.0f, 1.0f));
            if (std::abs(q.x) < 0.01f) continue;
            const float err = std::abs(glm::length(finiteDifferenceGradient(q, c.o, 1e-3f)) - 1.0f);
            worst = std::max(worst, err);
            EXPECT_LE(err, 1e-2f);
        }
        recordWorst(c.name, worst);
    }
}

} // namespace cutaway::test

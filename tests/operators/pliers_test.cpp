// Pliers (a compactly supported pull): the iterative backward map converges
// up to the contraction bound, fixed faces, the analytic Jacobian, identity.
#include "operator_test_util.hpp"

#include <vector>

namespace cutaway::test {
namespace {

struct PliersCase {
    const char* name;
    OperatorParams o;
};

// A displacement along `direction` whose contraction factor is `k`.
glm::vec3 displacementFor(float k, float radius, glm::vec3 direction) {
    return glm::normalize(direction) * (k * radius / CW_PLIERS_MAX_SLOPE);
}

std::vector<PliersCase> pliersCases() {
    return {
        {"typical", pliersParams({0.1f, -0.2f, 0.3f}, 0.5f, {0.1f, 0.15f, -0.05f})},
        // The ball touches all six faces; the validator's limit k = 0.95.
        {"extreme",
         pliersParams({0.0f, 0.0f, 0.0f}, 1.0f, displacementFor(0.95f, 1.0f, {1.0f, 1.0f, 1.0f}))},
        // Small, in a corner, pushing in.
        {"small", pliersParams({-0.7f, 0.6f, -0.75f}, 0.2f,
                               displacementFor(0.9f, 0.2f, {0.3f, 0.0f, -1.0f}))},
        // Beyond what the validator accepts, still below 1: convergence margin.
        {"nearOne",
         pliersParams({0.0f, 0.1f, 0.0f}, 0.8f, displacementFor(0.99f, 0.8f, {0.0f, -1.0f, 0.2f}))},
    };
}

// Even i: anywhere in the box; odd i: in the ball's bounding box.
glm::vec3 samplePliersPoint(Rng& rng, const OperatorParams& o, int i) {
    if (i % 2 == 0) return rng.inUnitBox();
    const glm::vec3 c(o.a);
    return rng.inBox(c - glm::vec3(o.a.w), c + glm::vec3(o.a.w));
}

} // namespace

TEST(Pliers, ContractionBoundIsTheProfilesSteepestSlope) {
    float steepest = 0.0f;
    for (int i = 0; i <= 100000; ++i) {
        const float u = static_cast<float>(i) / 100000.0f;
        steepest = std::max(steepest, std::abs(u * shader::pliersProfileSlopeOverU(u * u)));
    }
    EXPECT_NEAR(steepest, CW_PLIERS_MAX_SLOPE, 1e-5f);
    const OperatorParams o = pliersParams({0.0f, 0.0f, 0.0f}, 0.5f, {0.3f, 0.0f, 0.4f});
    EXPECT_NEAR(shader::pliersContraction(o), 0.5f * CW_PLIERS_MAX_SLOPE / 0.5f, 1e-6f);
    EXPECT_FALSE(shader::operatorParamsValid(o)) << "k = 1.72 must be refused";
    for (const PliersCase& c : pliersCases())
        EXPECT_TRUE(shader::operatorParamsValid(c.o)) << c.name;
}

TEST(Pliers, BackwardUndoesForward) {
    for (const PliersCase& c : pliersCases()) {
        SCOPED_TRACE(c.name);
        Rng rng(31);
        float worst = 0.0f;
        for (int i = 0; i < 10000; ++i) {
            const glm::vec3 p = samplePliersPoint(rng, c.o, i);
            const glm::vec4 back = shader::operatorBackward(shader::operatorForward(p, c.o), c.o);
            worst = std::max(worst, maxAbs(glm::vec3(back) - p));
            EXPECT_EQ(back.w, CW_NO_CUT);
        }
        EXPECT_LE(worst, 1e-5f);
        recordWorst(c.name, worst);
    }
}

TEST(Pliers, SupportStaysInsideTheBallSoTheFacesStayFixed) {
    for (const PliersCase& c : pliersCases()) {
        SCOPED_TRACE(c.name);
        const glm::vec3 centre(c.o.a);
        const float radius = c.o.a.w;
        Rng rng(32);
        for (int i = 0; i < 10000; ++i) {
            const glm::vec3 p = samplePliersPoint(rng, c.o, 1);
            if (glm::length(p - centre) >= radius) continue;
            EXPECT_LE(glm::length(shader::operatorForward(p, c.o) - centre),
                      radius * (1.0f + 1e-6f));
        }
        for (int axis = 0; axis < 3; ++axis)
            for (float side : {-1.0f, 1.0f})
                for (int i = 0; i < 1000; ++i) {
                    const glm::vec3 q = onFace(rng, axis, side);
                    EXPECT_EQ(glm::vec3(shader::operatorBackward(q, c.o)), q);
                    EXPECT_EQ(shader::operatorForward(q, c.o), q);
                }
    }
}

TEST(Pliers, ZeroDisplacementIsExactlyTheIdentity) {
    const OperatorParams o = pliersParams({0.1f, -0.2f, 0.3f}, 0.5f, {0.0f, 0.0f, 0.0f});
    Rng rng(33);
    for (int i = 0; i < 10000; ++i) {
        const glm::vec3 q = rng.inBox(glm::vec3(-1.5f), glm::vec3(1.5f));
        EXPECT_EQ(shader::operatorForward(q, o), q);
        EXPECT_EQ(shader::operatorBackward(q, o), glm::vec4(q, CW_NO_CUT));
        EXPECT_EQ(shader::operatorJacobian(q, o), glm::mat3(1.0f));
    }
}

TEST(Pliers, JacobianMatchesFiniteDifferences) {
    // Near k = 1 the backward map is steep (|J| up to 1 / (1 - k)) and sharply
    // curved: extrapolated differences keep the truncation error small.
    const float h = 3e-4f;
    for (const PliersCase& c : pliersCases()) {
        SCOPED_TRACE(c.name);
        Rng rng(34);
        float worst = 0.0f;
        // Beyond the validator's k < 0.95 float noise is amplified up to 1 / (1 - k).
        const float tolerance = shader::pliersContraction(c.o) > 0.95f ? 5e-3f : 2e-3f;
        for (int i = 0; i < 10000; ++i) {
            const glm::vec3 q = shader::operatorForward(samplePliersPoint(rng, c.o, i), c.o);
            const glm::mat3 analytic = shader::operatorJacobian(q, c.o);
            const float err = jacobianError(analytic, extrapolatedJacobian(q, c.o, h));
            worst = std::max(worst, err);
            EXPECT_LE(err, tolerance) << "q " << q.x << " " << q.y << " " << q.z;
        }
        recordWorst(c.name, worst);
    }
}

} // namespace cutaway::test

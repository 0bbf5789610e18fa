// Dilator (a volumetric magic lens): the radial profile is monotone and C1 over
// the whole parameter range, its closed-form inverse, round trip, fixed faces,
// the analytic Jacobian, identity.
#include "operator_test_util.hpp"

#include <vector>

namespace cutaway::test {
namespace {

struct DilatorCase {
    const char* name;
    OperatorParams o;
};

std::vector<DilatorCase> dilatorCases() {
    return {
        {"typical", dilatorParams(0.3f, 2.0f, false)},
        // m rho = 0.945: the blend region is squeezed to a slope of ~0.03.
        {"extreme", dilatorParams(0.45f, 2.1f, false)},
        {"strong", dilatorParams(0.09f, 10.0f, false)},
        {"shrink", dilatorParams(0.5f, 0.5f, false)},
        {"cylinder", dilatorParams(0.2f, 3.0f, true)},
    };
}

float radialLength(glm::vec3 q, const OperatorParams& o) {
    return o.a.z > 0.5f ? glm::length(glm::vec2(q)) : glm::length(q);
}

} // namespace

TEST(Dilator, ProfileIsMonotoneAndC1WheneverMagnifiedRadiusIsInside) {
    float worstInverse = 0.0f;
    for (float m : {0.1f, 0.5f, 0.9f, 1.5f, 2.0f, 4.0f, 10.0f})
        for (float rho : {0.0f, 0.05f, 0.2f, 0.4f, 0.6f, 0.9f, 0.98f}) {
            if (m * rho >= 0.99f) continue;
            SCOPED_TRACE(testing::Message() << "m " << m << " rho " << rho);
            EXPECT_TRUE(shader::operatorParamsValid(dilatorParams(rho, m, false)));
            float previous = -1.0f;
            for (int i = 0; i <= 4000; ++i) {
                const float r = 1.2f * static_cast<float>(i) / 4000.0f;
                const float f = shader::dilatorProfile(r, rho, m);
                EXPECT_GT(f, previous) << "r " << r;
                EXPECT_GT(shader::dilatorProfileSlope(r, rho, m), 0.0f);
                previous = f;
                worstInverse =
                    std::max(worstInverse, std::abs(shader::dilatorProfileInverse(f, rho, m) - r));
            }
            // C1 at both joints: from either side, difference quotients and
            // slopes converge to the joint's slope (linearly: a kink would not).
            for (float joint : {rho, 1.0f}) {
                const float f = shader::dilatorProfile(joint, rho, m);
                const float slope = shader::dilatorProfileSlope(joint, rho, m);
                for (float side : {-1.0f, 1.0f}) {
                    if (joint + side * 1e-3f < 0.0f) continue;
                    float quotientError[2];
                    float slopeError[2];
                    for (int k = 0; k < 2; ++k) {
                        const float step = side * (k == 0 ? 1e-3f : 1e-4f);
                        const float fs = shader::dilatorProfile(joint + step, rho, m);
                        quotientError[k] = std::abs((fs - f) / step - slope);
                        slopeError[k] =
                            std::abs(shader::dilatorProfileSlope(joint + step, rho, m) - slope);
                    }
                    EXPECT_LE(quotientError[1], 0.2f * quotientError[0] + 2e-3f) << joint;
                    EXPECT_LE(slopeError[1], 0.2f * slopeError[0] + 1e-4f) << joint;
                }
            }
            EXPECT_FLOAT_EQ(shader::dilatorProfile(1.0f, rho, m), 1.0f);
        }
    EXPECT_LE(worstInverse, 2e-5f);
    recordWorst("inverse", worstInverse);
    EXPECT_FALSE(shader::operatorParamsValid(dilatorParams(0.5f, 2.0f, false))) << "m rho = 1";
}

TEST(Dilator, BackwardUndoesForward) {
    for (const DilatorCase& c : dilatorCases()) {
        SCOPED_TRACE(c.name);
        Rng rng(41);
        float worst = 0.0f;
        for (int i = 0; i < 10000; ++i) {
            const glm::vec3 p = rng.inUnitBox();
            const glm::vec4 back = shader::operatorBackward(shader::operatorForward(p, c.o), c.o);
            worst = std::max(worst, maxAbs(glm::vec3(back) - p));
            EXPECT_EQ(back.w, CW_NO_CUT);
        }
        EXPECT_LE(worst, 1e-4f); // rounding grows like 1 / min F' (~0.01 for "strong")
        recordWorst(c.name, worst);
    }
}

TEST(Dilator, BoxFacesStayFixed) {
    for (const DilatorCase& c : dilatorCases()) {
        SCOPED_TRACE(c.name);
        Rng rng(42);
        // The cylinder runs through z = +-1: only its four side faces are fixed.
        const int axes = c.o.a.z > 0.5f ? 2 : 3;
        for (int axis = 0; axis < axes; ++axis)
            for (float side : {-1.0f, 1.0f})
                for (int i = 0; i < 1000; ++i) {
                    const glm::vec3 q = onFace(rng, axis, side);
                    EXPECT_EQ(glm::vec3(shader::operatorBackward(q, c.o)), q);
                    EXPECT_EQ(shader::operatorForward(q, c.o), q);
                    EXPECT_EQ(shader::operatorJacobian(q, c.o), glm::mat3(1.0f));
                }
    }
}

TEST(Dilator, UnitMagnificationIsExactlyTheIdentity) {
    for (bool cylinder : {false, true}) {
        const OperatorParams o = dilatorParams(0.3f, 1.0f, cylinder);
        Rng rng(43);
        for (int i = 0; i < 10000; ++i) {
            const glm::vec3 q = rng.inBox(glm::vec3(-1.5f), glm::vec3(1.5f));
            EXPECT_EQ(shader::operatorForward(q, o), q);
            EXPECT_EQ(shader::operatorBackward(q, o), glm::vec4(q, CW_NO_CUT));
            EXPECT_EQ(shader::operatorJacobian(q, o), glm::mat3(1.0f));
        }
    }
}

TEST(Dilator, JacobianMatchesFiniteDifferences) {
    // Strong lenses curve F sharply (F' dips to ~0.003 for m = 10, rho = 0.09):
    // extrapolated differences keep the truncation error below float noise.
    const float h = 3e-4f;
    for (const DilatorCase& c : dilatorCases()) {
        SCOPED_TRACE(c.name);
        const float rho = c.o.a.x;
        const float m = c.o.a.y;
        Rng rng(44);
        float worst = 0.0f;
        for (int i = 0; i < 10000; ++i) {
            const glm::vec3 q = rng.inBox(glm::vec3(-1.2f), glm::vec3(1.2f));
            // F is C1, not C2, at r = rho and r = 1 (deformed radii m rho and 1).
            const float y = radialLength(q, c.o);
            if (std::abs(y - m * rho) < 2.0f * h || std::abs(y - 1.0f) < 2.0f * h) continue;
            const glm::mat3 analytic = shader::operatorJacobian(q, c.o);
            const float err = jacobianError(analytic, extrapolatedJacobian(q, c.o, h));
            worst = std::max(worst, err);
            EXPECT_LE(err, 2e-3f) << "q " << q.x << " " << q.y << " " << q.z;
        }
        recordWorst(c.name, worst);
    }
}

TEST(Operators, UnknownKindIsTheIdentity) {
    OperatorParams o = dilatorParams(0.3f, 2.0f, false);
    o.kind.x = 7.0f;
    const glm::vec3 q(0.1f, -0.2f, 0.3f);
    EXPECT_TRUE(shader::operatorIsIdentity(o));
    EXPECT_FALSE(shader::operatorParamsValid(o));
    EXPECT_EQ(shader::operatorBackward(q, o), glm::vec4(q, CW_NO_CUT));
    EXPECT_EQ(shader::operatorJacobian(q, o), glm::mat3(1.0f));
}

} // namespace cutaway::test

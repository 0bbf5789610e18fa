// Helpers for the operator tests: parameter builders, seeded random points and
// finite differences of the shared backward map (shaders/shared/operators.h).
#pragma once

#include "shared/operators.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <random>

namespace cutaway::test {

using shader::OperatorParams;

constexpr float kPi = 3.14159265f;

inline OperatorParams peelerParams(float hinge, float thickness, float radius, float angle,
                                   float halfWidth) {
    OperatorParams o{};
    o.a = glm::vec4(hinge, thickness, radius, angle);
    o.b = glm::vec4(halfWidth, 0.0f, 1.0f, 1.0f); // a cube: its frame is the unit box's
    o.kind.x = CW_OP_PEELER;
    return o;
}

inline OperatorParams retractorParams(float halfLength, float depth, float halfOpening) {
    OperatorParams o{};
    o.a = glm::vec4(halfLength, depth, halfOpening, 0.0f);
    o.kind.x = CW_OP_RETRACTOR;
    return o;
}

inline OperatorParams pliersParams(glm::vec3 centre, float radius, glm::vec3 displacement) {
    OperatorParams o{};
    o.a = glm::vec4(centre, radius);
    o.b = glm::vec4(displacement, 0.0f);
    o.kind.x = CW_OP_PLIERS;
    return o;
}

inline OperatorParams dilatorParams(float innerRadius, float magnification, bool cylinder) {
    OperatorParams o{};
    o.a = glm::vec4(innerRadius, magnification, cylinder ? 1.0f : 0.0f, 0.0f);
    o.kind.x = CW_OP_DILATOR;
    return o;
}

// Uniform points from a fixed seed, so every run tests the same points.
class Rng {
public:
    explicit Rng(unsigned seed) : m_gen(seed) {}
    float uniform(float lo, float hi) {
        return std::uniform_real_distribution<float>(lo, hi)(m_gen);
    }
    glm::vec3 inBox(glm::vec3 lo, glm::vec3 hi) {
        return glm::vec3(uniform(lo.x, hi.x), uniform(lo.y, hi.y), uniform(lo.z, hi.z));
    }
    glm::vec3 inUnitBox() { return inBox(glm::vec3(-1.0f), glm::vec3(1.0f)); }

private:
    std::mt19937 m_gen;
};

inline glm::vec3 backward(glm::vec3 q, const OperatorParams& o) {
    return glm::vec3(shader::operatorBackward(q, o));
}

inline float signedDistance(glm::vec3 q, const OperatorParams& o) {
    return shader::operatorBackward(q, o).w;
}

// Central differences of T_B's xyz, column j = d T_B / d q_j, step h.
inline glm::mat3 finiteDifferenceJacobian(glm::vec3 q, const OperatorParams& o, float h) {
    glm::mat3 j(0.0f);
    for (int c = 0; c < 3; ++c) {
        glm::vec3 step(0.0f);
        step[c] = h;
        j[c] = (backward(q + step, o) - backward(q - step, o)) / (2.0f * h);
    }
    return j;
}

// Richardson-extrapolated central differences (error O(h^4) instead of
// O(h^2)), for maps with large third derivatives.
inline glm::mat3 extrapolatedJacobian(glm::vec3 q, const OperatorParams& o, float h) {
    return (4.0f * finiteDifferenceJacobian(q, o, 0.5f * h) - finiteDifferenceJacobian(q, o, h)) /
           3.0f;
}

// Central differences of the signed distance w.
inline glm::vec3 finiteDifferenceGradient(glm::vec3 q, const OperatorParams& o, float h) {
    glm::vec3 g(0.0f);
    for (int c = 0; c < 3; ++c) {
        glm::vec3 step(0.0f);
        step[c] = h;
        g[c] = (signedDistance(q + step, o) - signedDistance(q - step, o)) / (2.0f * h);
    }
    return g;
}

inline float maxAbs(const glm::mat3& m) {
    float r = 0.0f;
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < 3; ++i)
            r = std::max(r, std::abs(m[c][i]));
    return r;
}

inline float maxAbs(glm::vec3 v) {
    return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

// Relative difference of an analytic and a finite-difference Jacobian: the
// largest element difference over max(1, largest element).
inline float jacobianError(const glm::mat3& analytic, const glm::mat3& numeric) {
    return maxAbs(analytic - numeric) / std::max(1.0f, maxAbs(analytic));
}

// A random point on the face (axis, side = -1 or 1) of the unit box.
inline glm::vec3 onFace(Rng& rng, int axis, float side) {
    glm::vec3 p = rng.inUnitBox();
    p[axis] = side;
    return p;
}

// Measured worst errors go into the test's XML record
// (--gtest_output=xml:FILE) so the tolerances can be compared with them.
inline void recordWorst(const char* name, float value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", static_cast<double>(value));
    ::testing::Test::RecordProperty(name, text);
}

} // namespace cutaway::test

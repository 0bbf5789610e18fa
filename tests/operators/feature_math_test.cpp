// The feature-alignment math of shaders/shared/feature.h, as the operator
// shader runs it: Eq. 4's three cases, surface alignment's mask and beta
// (Eq. 9), gamma (Eq. 10), and segment-aware gradients (section 4.3).
#include "shared/feature.h"

#include <gtest/gtest.h>

namespace cutaway::test {
namespace {

using namespace cutaway::shader;

TEST(FeatureMath, Equation4HasThreeCases) {
    // Case 1: neither p' nor p0 is feature, p0 exists: the point moves.
    EXPECT_EQ(featureCase(true, 0.2f, true, 0.1f), CW_CASE_TRANSFORMED);
    // Case 2: p' is feature: it stays, whatever the operator would bring there,
    // even inside a cut (p0 invalid) and even outside a pre-image.
    EXPECT_EQ(featureCase(true, 0.0f, true, 0.5f), CW_CASE_MASKED);
    EXPECT_EQ(featureCase(false, 0.0f, true, 0.9f), CW_CASE_MASKED);
    EXPECT_EQ(featureCase(true, 0.9f, true, 0.7f), CW_CASE_MASKED);
    // Case 3: the feature would be dragged out of place (p0 is feature, p' is
    // not), or a cut / opening with no feature: empty.
    EXPECT_EQ(featureCase(true, 0.5f, true, 0.2f), CW_CASE_EMPTY);
    EXPECT_EQ(featureCase(false, 0.0f, true, 0.2f), CW_CASE_EMPTY);
    EXPECT_EQ(featureCase(false, 0.0f, false, 0.0f), CW_CASE_EMPTY);
    // Axis alignment (M = 0 everywhere) is Eq. 6: p0 if it exists, else empty.
    EXPECT_EQ(featureCase(true, 0.0f, true, 0.0f), CW_CASE_TRANSFORMED);
    EXPECT_EQ(featureCase(false, 0.0f, true, 0.0f), CW_CASE_EMPTY);
}

TEST(FeatureMath, SurfaceMaskIsFeatureExactlyFromTheDepthOn) {
    const float tau = 5.0f;
    for (float delta : {0.0f, 0.5f, 2.0f}) {
        for (float dt = 0.0f; dt < 12.0f; dt += 0.125f) {
            EXPECT_EQ(surfaceMask(dt, tau, delta) >= 0.5f, dt >= tau) << dt << " " << delta;
            EXPECT_GE(surfaceMask(dt, tau, delta), 0.0f);
            EXPECT_LE(surfaceMask(dt, tau, delta), 1.0f);
        }
    }
}

TEST(FeatureMath, BetaOfEquation9AtTheBandEdges) {
    const float tau = 5.0f, delta = 2.0f;
    EXPECT_FLOAT_EQ(surfaceBeta(tau, tau, delta), 1.0f);         // on the cut, feature side
    EXPECT_FLOAT_EQ(surfaceBeta(tau + delta, tau, delta), 0.0f); // band ends
    EXPECT_FLOAT_EQ(surfaceBeta(tau + 0.5f * delta, tau, delta), 0.5f);
    EXPECT_NEAR(surfaceBeta(tau - 1e-4f, tau, delta), -1.0f, 1e-3f); // moving side: turned over
    EXPECT_FLOAT_EQ(surfaceBeta(tau - delta, tau, delta), 0.0f);
    EXPECT_FLOAT_EQ(surfaceBeta(tau - 0.5f * delta, tau, delta), -0.5f);
    EXPECT_FLOAT_EQ(surfaceBeta(0.0f, tau, delta), 0.0f);
    EXPECT_FLOAT_EQ(surfaceBeta(20.0f, tau, delta), 0.0f);
    EXPECT_FLOAT_EQ(surfaceBeta(tau, tau, 0.0f), 0.0f); // no band, no blend
    // The blend: beta = 1 gives the distance field's normal, -1 its opposite.
    const vec3 t(1, 0, 0), d(0, 0, 1);
    EXPECT_EQ(surfaceNormal(t, d, 1.0f), d);
    EXPECT_EQ(surfaceNormal(t, d, -1.0f), -d);
    EXPECT_EQ(surfaceNormal(t, d, 0.0f), t);
}

TEST(FeatureMath, GammaOfEquation10AtTheBandEdges) {
    EXPECT_FLOAT_EQ(segmentGamma(0.0f), 0.0f);
    EXPECT_FLOAT_EQ(segmentGamma(0.25f), 0.5f);
    EXPECT_NEAR(segmentGamma(0.5f - 1e-5f), 1.0f, 1e-4f);
    EXPECT_FLOAT_EQ(segmentGamma(0.5f), 0.0f); // the feature keeps its normal
    EXPECT_FLOAT_EQ(segmentGamma(1.0f), 0.0f);
    const vec3 t(0, 1, 0);
    EXPECT_EQ(segmentNormal(t, 0.0f), t);
    EXPECT_EQ(segmentNormal(t, 1.0f), -t); // turned over next to the feature
    EXPECT_EQ(segmentNormal(t, 0.5f), vec3(0.0f));
}

TEST(FeatureMath, SegmentMaskKeepsEveryVoxelOfTheSegment) {
    EXPECT_GE(segmentMask(0.1f, true),
              0.5f); // a segment voxel is feature even where smoothing thins it
    EXPECT_LT(segmentMask(0.3f, false), 0.5f);
    EXPECT_EQ(segmentMask(0.8f, false), 0.8f); // the smooth field still counts
}

// Trilinear interpolation along one axis of two voxel gradients.
float lerp(float a, float b, float t) {
    return a + (b - a) * t;
}

TEST(FeatureMath, SegmentAwareGradientsSurviveInterpolationAcrossABoundary) {
    // A row of labels: 1 1 1 | 2 2 2, segment of interest 1, 1 mm voxels.
    const int labels[6] = {1, 1, 1, 2, 2, 2};
    const auto in = [&](int i, int segment) {
        return labels[std::max(0, std::min(5, i))] == segment;
    };
    // Section 4.3: neighbours count 1 in the segment of interest, 0 elsewhere,
    // on both sides of the boundary.
    const float left = segmentDifference(in(1, 1), in(3, 1), 1.0f);  // voxel 2, in the segment
    const float right = segmentDifference(in(2, 1), in(4, 1), 1.0f); // voxel 3, outside it
    EXPECT_LT(left, 0.0f);                                           // into the segment: toward -x
    EXPECT_LT(right, 0.0f);                    // same direction on the other side
    EXPECT_LT(lerp(left, right, 0.5f), -0.4f); // non-zero half-way between them
    // Each voxel's own segment instead (two-pass rendering): the gradients are
    // opposite and interpolate to zero on the boundary.
    const float ownLeft = segmentDifference(in(1, 1), in(3, 1), 1.0f);
    const float ownRight = segmentDifference(in(2, 2), in(4, 2), 1.0f);
    EXPECT_FLOAT_EQ(lerp(ownLeft, ownRight, 0.5f), 0.0f);
}

TEST(FeatureMath, FieldGradientIsTheUnitDirectionPerMillimetre) {
    // A linear field f = a . x (x in mm) sampled one voxel either side: the
    // direction is a's, whatever the spacing; per-voxel differences alone would
    // tilt it toward the coarse axis.
    const glm::vec3 a(1.0f, 2.0f, -0.5f);
    const glm::vec3 spacing(0.5f, 1.0f, 3.0f);
    const glm::vec3 below = -a * spacing; // f(x - spacing_i e_i) - f(x), with f(x) = 0
    const glm::vec3 above = a * spacing;
    const glm::vec3 g = featureGradientOf(below, above, 0.5f / spacing);
    EXPECT_NEAR(glm::length(g), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::distance(g, glm::normalize(a)), 0.0f, 1e-6f);
    const glm::vec3 perVoxel = glm::normalize(above - below);
    EXPECT_GT(glm::distance(perVoxel, glm::normalize(a)), 0.1f);
    // A flat field has no direction (the blends of Eq. 9, 10 then change nothing).
    EXPECT_EQ(featureGradientOf(glm::vec3(4.0f), glm::vec3(4.0f), 0.5f / spacing), glm::vec3(0.0f));
}

} // namespace
} // namespace cutaway::test

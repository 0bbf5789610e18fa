// The peeler in a box that is not a cube: its parameters are millimetres, and
// a fold is rigid, so the flap keeps its thickness and its skin its length in
// the world whatever the box's proportions; and the maps' invariants (round
// trip, Jacobian) hold in the unit box's own units, where the peeler's frame
// of equal units is converted (shaders/shared/operators.h).
#include "operator_test_util.hpp"
#include "scene/scene.hpp"

#include <nlohmann/json.hpp>
#include <string>

namespace cutaway::test {
namespace {

// A peeler in a box of `scale` mm, parsed as a scene gives it.
OperatorSpec parsedPeeler(const std::string& scale, const std::string& params) {
    const Scene scene =
        parseScene(nlohmann::json::parse(R"({"version": 1, "volume": {"phantom": "head"},
        "operators": [{"type": "peeler", "placement": {"scale": )" +
                                         scale + R"(}, "params": )" + params + "}]}"),
                   "/nonexistent", "peeler shape test");
    return scene.operators.at(0);
}

// T_F in world millimetres: A T_F(A^-1 p).
glm::dvec3 forwardMm(const OperatorSpec& op, glm::dvec3 p) {
    const glm::dvec3 local(glm::inverse(op.localToWorld) * glm::dvec4(p, 1.0));
    const glm::dvec3 moved(shader::operatorForward(glm::vec3(local), op.params));
    return glm::dvec3(op.localToWorld * glm::dvec4(moved, 1.0));
}

constexpr double kHinge = -20.0, kThickness = 8.0, kRadius = 4.0;
const std::string kParams = R"({"hinge": -20, "thickness": 8, "radius": 4, "angle": 90})";

} // namespace

// Box 100 x 80 x 40 mm: in the unit box's units the layer would turn upright
// 2.5x thicker and its skin 2.5x shorter.
TEST(PeelerShape, AnOblongBoxFoldsItsLayerRigidly) {
    for (const std::string scale : {"[100, 80, 40]", "[50, 80, 40]", "[60, 30, 90]"}) {
        SCOPED_TRACE(scale);
        const OperatorSpec op = parsedPeeler(scale, kParams);
        const glm::dvec3 half(glm::length(glm::dvec3(op.localToWorld[0])),
                              glm::length(glm::dvec3(op.localToWorld[1])),
                              glm::length(glm::dvec3(op.localToWorld[2])));
        const double top = half.z, end = half.x;
        int straight = 0;
        // Along the layer, skin and underside at the same arc length stay a
        // thickness apart, and the skin keeps its length.
        const int n = 200;
        glm::dvec3 previousSkin{};
        double skinLength = 0.0;
        for (int i = 1; i < n; ++i) {
            const double x = kHinge + (end - kHinge) * i / n;
            const glm::dvec3 skin = forwardMm(op, {x, 0.0, top - 1e-4});
            const glm::dvec3 under = forwardMm(op, {x, 0.0, top - kThickness + 1e-4});
            EXPECT_NEAR(glm::length(skin - under), kThickness, 1e-2) << "x " << x;
            if (i > 1) skinLength += glm::length(skin - previousSkin);
            previousSkin = skin;
            // Past the bend (90 degrees: arc length R pi / 2) the flap stands
            // upright: a rigid motion of the layer.
            if (x - kHinge > kRadius * 1.5708 + 1e-3) {
                ++straight;
                const glm::dvec3 other = forwardMm(op, {x, 0.3 * half.y, top - 0.5 * kThickness});
                const glm::dvec3 original(x, 0.3 * half.y, top - 0.5 * kThickness);
                EXPECT_NEAR(glm::length(other - skin),
                            glm::length(original - glm::dvec3(x, 0.0, top - 1e-4)), 1e-2);
                EXPECT_NEAR(skin.x, kHinge + kRadius, 1e-2) << "upright, a radius from the hinge";
            }
        }
        const double expected = (end - kHinge) * (n - 2) / n;
        EXPECT_NEAR(skinLength, expected, 2e-3 * expected);
        EXPECT_GT(straight, n / 2);
    }
}

// The round trip and the analytic Jacobian in the unit box's units, for an
// oblong box (the peeler's own tests use cubes, where its frame is the box's).
TEST(PeelerShape, MapsAgreeInTheUnitBoxOfAnOblongBox) {
    const OperatorSpec op = parsedPeeler("[100, 80, 40]", kParams);
    const OperatorParams& o = op.params;
    Rng rng(23);
    int lifted = 0, compared = 0;
    for (int i = 0; i < 20000; ++i) {
        const glm::vec3 p = rng.inUnitBox();
        const glm::vec3 q = shader::operatorForward(p, o);
        if (q == p) continue;
        ++lifted;
        const glm::vec4 back = shader::operatorBackward(q, o);
        EXPECT_LE(maxAbs(glm::vec3(back) - p), 1e-5f);
        EXPECT_GT(back.w, 0.0f);
        // Away from the bend's ends, where the map is only C0.
        if (back.w < 0.01f) continue;
        const float angle = (p.x * 50.0f - float(kHinge)) / float(kRadius); // on the bend
        if (angle < 0.05f || std::abs(angle - 1.5708f) < 0.05f) continue;
        ++compared;
        const float err =
            jacobianError(shader::operatorJacobian(q, o), finiteDifferenceJacobian(q, o, 1e-3f));
        EXPECT_LE(err, 2e-3f) << "q " << q.x << " " << q.y << " " << q.z;
    }
    EXPECT_GT(lifted, 500);
    EXPECT_GT(compared, 400);
}

} // namespace cutaway::test

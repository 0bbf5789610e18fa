// Peeler (a bend, Barr's global deformation): round trip, the hole is empty,
// fixed faces, the analytic Jacobian, a signed distance with unit gradient at
// the cut faces and a pre-image continuous across them, for a typical, an
// extreme and two shallow folds.
#include "operator_test_util.hpp"
#include "operators/operator_geometry.hpp"

#include <string>
#include <vector>

namespace cutaway::test {
namespace {

struct PeelerCase {
    const char* name;
    OperatorParams o;
};

std::vector<PeelerCase> peelerCases() {
    return {
        {"typical", peelerParams(-0.2f, 0.3f, 0.2f, 2.0f, 0.6f)},
        // Thick, sharp, folded flat back, the whole width: |y| = 1 are cuts.
        {"extreme", peelerParams(-0.9f, 1.5f, 0.02f, kPi, 1.0f)},
        // Shallow fold whose straight part still lies in the hole it left.
        {"shallow", peelerParams(-0.5f, 0.4f, 0.3f, 0.25f, 0.8f)},
        // Large radius: the flap ends on the bend (1 - h < R theta).
        {"endOnBend", peelerParams(0.5f, 0.1f, 2.0f, 0.5f, 0.3f)},
        // Thick (the gallery's scalp flap): the underside bends through the
        // material past x = 1, (1 - h)^2 + R^2 < (R + t)^2.
        {"thick", peelerParams(-25.0f / 60.0f, 1.5f, 0.5f, 130.0f * kPi / 180.0f, 35.0f / 55.0f)},
    };
}

float hingeOf(const OperatorParams& o) {
    return o.a.x;
}
float thicknessOf(const OperatorParams& o) {
    return o.a.y;
}
float radiusOf(const OperatorParams& o) {
    return o.a.z;
}
float angleOf(const OperatorParams& o) {
    return o.a.w;
}
float halfWidthOf(const OperatorParams& o) {
    return std::min(o.b.x, 1.0f);
}

// -1 off the flap, 0 on its bend, 1 on its straight part.
int flapPart(glm::vec3 q, const OperatorParams& o) {
    return static_cast<int>(shader::peelerFlapCoords(q, o).z);
}

// Which expression the backward map takes at q: flapPart, except -3 where it
// is the identity.
int mapPiece(glm::vec3 q, const OperatorParams& o) {
    const glm::vec3 f = shader::peelerFlapCoords(q, o);
    if (f.z >= 0.0f) return static_cast<int>(f.z);
    return shader::peelerContinues(q, f, shader::peelerFlapDistance(q, o), o)
               ? static_cast<int>(f.z)
               : -3;
}

// A point of the lifted layer, not within `margin` of its boundary.
bool liftedWithMargin(glm::vec3 p, const OperatorParams& o, float margin) {
    const float e = 1.0f - p.z;
    return p.x > hingeOf(o) + margin && p.x < 1.0f - margin &&
           std::abs(p.y) < halfWidthOf(o) - margin && e > margin && e < thicknessOf(o) - margin;
}

// Even i: anywhere in the box; odd i: in the layer that is lifted.
glm::vec3 samplePeelerPoint(Rng& rng, const OperatorParams& o, int i) {
    if (i % 2 == 0) return rng.inUnitBox();
    return rng.inBox(glm::vec3(hingeOf(o), -halfWidthOf(o), 1.0f - thicknessOf(o)),
                     glm::vec3(1.0f, halfWidthOf(o), 1.0f));
}

// A texel of a baked map, and the half gap its parameters get (b.y).
constexpr float kTexel = 0.04f;
OperatorParams sampled(OperatorParams o) {
    o.b.y = kTexel;
    return o;
}

// Whether untouched material at q lies in the gap carved around the flap.
bool inGap(glm::vec3 q, const OperatorParams& o) {
    return q.z <= 1.0f && !shader::peelerInHole(q, o) && flapPart(q, o) < 0 &&
           shader::peelerInGap(q, shader::peelerFlapCoords(q, o), shader::peelerFlapDistance(q, o),
                               o);
}

bool nearLayerBoundary(glm::vec3 p, const OperatorParams& o, float margin) {
    const float e = 1.0f - p.z;
    return std::abs(p.x - hingeOf(o)) < margin ||
           std::abs(std::abs(p.y) - halfWidthOf(o)) < margin ||
           std::abs(e - thicknessOf(o)) < margin || 1.0f - p.x < margin;
}

} // namespace

TEST(Peeler, BackwardUndoesForward) {
    for (const PeelerCase& c : peelerCases()) {
        SCOPED_TRACE(c.name);
        const OperatorParams o = sampled(c.o); // as baked: with the gap
        Rng rng(11);
        float worst = 0.0f;
        int lifted = 0;
        for (int i = 0; i < 20000; ++i) {
            const glm::vec3 p = samplePeelerPoint(rng, o, i);
            if (nearLayerBoundary(p, o, 1e-5f)) continue; // rounding may pick the other side
            if (inGap(p, o)) continue; // carved: see AGapPartsTheFlapFromMaterialItSweptInto
            const glm::vec4 back = shader::operatorBackward(shader::operatorForward(p, o), o);
            worst = std::max(worst, maxAbs(glm::vec3(back) - p));
            EXPECT_GT(back.w, 0.0f) << "p " << p.x << " " << p.y << " " << p.z;
            lifted += liftedWithMargin(p, o, 0.0f) ? 1 : 0;
        }
        EXPECT_LE(worst, 1e-5f);
        EXPECT_GT(lifted, 9000) << "the test should move much of the layer";
        recordWorst(c.name, worst);
    }
}

TEST(Peeler, TheHoleIsEmptyAndMapsNearItself) {
    for (const PeelerCase& c : peelerCases()) {
        SCOPED_TRACE(c.name);
        const OperatorParams& o = c.o;
        Rng rng(12);
        const glm::vec3 lo(hingeOf(o), -halfWidthOf(o), 1.0f - thicknessOf(o));
        const glm::vec3 hi(1.0f, halfWidthOf(o), 1.0f);
        // Where the bend starts it still covers the hole; beyond this reach,
        // a fold past a right angle has left the hole entirely empty.
        const float reach = std::sqrt(thicknessOf(o) * (thicknessOf(o) + 2.0f * radiusOf(o)));
        int empty = 0;
        int continued = 0;
        for (int i = 0; i < 10000; ++i) {
            const glm::vec3 q = rng.inBox(lo, hi);
            const glm::vec4 back = shader::operatorBackward(q, o);
            if (back.w > 0.0f) {
                // Only the flap may have a pre-image here, and then a genuine one.
                const glm::vec3 p(back);
                EXPECT_TRUE(liftedWithMargin(p, o, -1e-6f));
                EXPECT_LE(maxAbs(shader::operatorForward(p, o) - q), 1e-5f);
                if (angleOf(o) >= 0.5f * kPi) {
                    EXPECT_LE(q.x - hingeOf(o), reach + 1e-4f);
                }
                continue;
            }
            ++empty;
            // The identity, or next to the flap its pre-image continued: then
            // about as far outside the layer as q is from the flap.
            if (glm::vec3(back) == q) continue;
            ++continued;
            const float d = shader::peelerFlapDistance(q, o);
            const float outside = shader::distanceToBox(glm::vec3(back), lo, hi);
            EXPECT_LE(outside, 1.001f * d + 1e-5f) << q.x << " " << q.y << " " << q.z;
        }
        if (angleOf(o) >= 0.5f * kPi && hingeOf(o) + reach + 0.01f < 1.0f) {
            // On purpose: points of the hole past the bend's reach are all empty.
            for (int i = 0; i < 2000; ++i) {
                const glm::vec3 q = rng.inBox(lo + glm::vec3(reach + 0.01f, 0.0f, 0.0f), hi);
                EXPECT_LE(signedDistance(q, o), 0.0f) << q.x << " " << q.y << " " << q.z;
            }
        }
        EXPECT_GT(empty, 1000);
        EXPECT_GT(continued, 10) << "the test should reach the flap's neighbourhood";
    }
}

// The baked map is interpolated between texels, so its pre-image must not
// jump where w changes sign: across the flap's cut faces (underside, sides,
// end) the empty side continues the flap's pre-image. With the identity there,
// the cut face showed tissue from a flap's length away in a band a texel wide.
TEST(Peeler, PreimageIsContinuousAcrossTheFlapsCutFaces) {
    const float delta = 2e-3f;
    for (const PeelerCase& c : peelerCases()) {
        SCOPED_TRACE(c.name);
        const OperatorParams& o = c.o;
        const float h = hingeOf(o);
        const float t = thicknessOf(o);
        const float hw = halfWidthOf(o);
        Rng rng(17);
        float worst = 0.0f;
        int crossings = 0;
        // p: a point of the layer just inside a cut face; `out`: the face's
        // outward normal after the fold.
        auto cross = [&](glm::vec3 p, glm::vec3 out) {
            const glm::vec3 inside = shader::operatorForward(p, o);
            const glm::vec3 beyond = inside + 2.0f * delta * out;
            const glm::vec4 a = shader::operatorBackward(inside, o);
            const glm::vec4 b = shader::operatorBackward(beyond, o);
            ASSERT_GT(a.w, 0.0f);
            if (b.w > 0.0f || flapPart(beyond, o) >= 0) return; // material or flap beyond
            // A flap barely lifted leaves a hole thinner than the step: beyond
            // lies nearer the hole's floor or walls, where the identity holds.
            // Likewise where the flap lies on the untouched material.
            if (shader::peelerUntouchedDistance(beyond, o) < 4.0f * delta) return;
            const float jump = maxAbs(glm::vec3(b) - glm::vec3(a));
            worst = std::max(worst, jump);
            ++crossings;
            EXPECT_LE(jump, 2.0f * delta * 1.01f + 1e-5f)
                << "q " << beyond.x << " " << beyond.y << " " << beyond.z;
        };
        for (int i = 0; i < 3000; ++i) {
            const float x = h + rng.uniform(0.1f, 0.9f) * (1.0f - h);
            const float y = rng.uniform(-0.9f, 0.9f) * hw;
            const float z = 1.0f - rng.uniform(0.1f, 0.9f) * t;
            // Underside: across the layer, from its middle outward.
            const glm::vec3 under(x, y, 1.0f - t + delta);
            cross(under,
                  glm::normalize(shader::operatorForward(under, o) -
                                 shader::operatorForward(glm::vec3(x, y, 1.0f - 0.5f * t), o)));
            // Sides: the bend leaves y alone.
            const float side = std::copysign(hw - delta, y);
            cross(glm::vec3(x, side, z), glm::vec3(0.0f, std::copysign(1.0f, y), 0.0f));
            // End, where the flap ends on its straight part: along tau(theta).
            if (shader::peelerFlapEnd(o).y > 0.0f) {
                cross(glm::vec3(1.0f - delta, y, z), shader::peelerTangent(angleOf(o)));
            }
        }
        EXPECT_GT(crossings, 1500);
        recordWorst(c.name, worst);
    }
}

TEST(Peeler, ZeroAngleIsExactlyTheIdentity) {
    const OperatorParams o = peelerParams(-0.2f, 0.3f, 0.2f, 0.0f, 0.6f);
    Rng rng(13);
    for (int i = 0; i < 10000; ++i) {
        const glm::vec3 q = rng.inBox(glm::vec3(-1.5f), glm::vec3(1.5f));
        EXPECT_EQ(shader::operatorForward(q, o), q);
        EXPECT_EQ(shader::operatorBackward(q, o), glm::vec4(q, CW_NO_CUT));
        EXPECT_EQ(shader::operatorJacobian(q, o), glm::mat3(1.0f));
    }
}

TEST(Peeler, UntouchedFacesStayFixed) {
    for (const PeelerCase& c : peelerCases()) {
        SCOPED_TRACE(c.name);
        const OperatorParams o = sampled(c.o); // as baked: with the gap
        Rng rng(14);
        std::vector<std::pair<int, float>> faces = {{0, -1.0f}, {2, -1.0f}};
        if (halfWidthOf(o) < 1.0f) faces.insert(faces.end(), {{1, -1.0f}, {1, 1.0f}});
        for (const auto& [axis, side] : faces)
            for (int i = 0; i < 2000; ++i) {
                const glm::vec3 q = onFace(rng, axis, side);
                if (inGap(q, o)) continue; // a flap folded flat back lies on the face's top
                const glm::vec4 back = shader::operatorBackward(q, o);
                EXPECT_LE(maxAbs(glm::vec3(back) - q), 1e-6f);
                EXPECT_GT(back.w, 0.0f);
                EXPECT_LE(maxAbs(shader::operatorForward(q, o) - q), 1e-6f);
            }
    }
}

TEST(Peeler, JacobianMatchesFiniteDifferences) {
    const float h = 1e-3f;
    for (const PeelerCase& c : peelerCases()) {
        SCOPED_TRACE(c.name);
        const OperatorParams& o = c.o;
        Rng rng(15);
        const float top = 1.0f + 2.0f * radiusOf(o) + thicknessOf(o);
        float worst = 0.0f;
        int onFlap = 0;
        for (int i = 0; i < 10000; ++i) {
            // Half on the moved material, half anywhere in the deformed box.
            const glm::vec3 q =
                i % 2 ? shader::operatorForward(samplePeelerPoint(rng, o, 1), o)
                      : rng.inBox(glm::vec3(-1.5f, -1.0f, -1.0f), glm::vec3(1.5f, 1.0f, top));
            const int part = flapPart(q, o);
            const int piece = mapPiece(q, o);
            // The map is only C0 across the flap's outline, the hinge and
            // phi = theta, and jumps where the continued pre-image gives way
            // to the identity.
            bool straddles = false;
            for (int axis = 0; axis < 3 && !straddles; ++axis)
                for (float side : {-2.0f * h, 2.0f * h}) {
                    glm::vec3 step(0.0f);
                    step[axis] = side;
                    straddles = straddles || mapPiece(q + step, o) != piece;
                }
            if (straddles) continue;
            onFlap += part >= 0 ? 1 : 0;
            const glm::mat3 analytic = shader::operatorJacobian(q, o);
            const float err = jacobianError(analytic, finiteDifferenceJacobian(q, o, h));
            worst = std::max(worst, err);
            EXPECT_LE(err, 2e-3f) << "q " << q.x << " " << q.y << " " << q.z << " part " << part;
        }
        EXPECT_GT(onFlap, 3000);
        recordWorst(c.name, worst);
    }
}

// The renderer's band |w| < D and cut normal grad w must be in real units.
TEST(Peeler, SignedDistanceHasUnitGradientAtTheCuts) {
    const float h = 1e-3f;
    for (const PeelerCase& c : peelerCases()) {
        SCOPED_TRACE(c.name);
        const OperatorParams& o = c.o;
        const float t = thicknessOf(o);
        const float hw = halfWidthOf(o);
        const float floorZ = 1.0f - t;
        Rng rng(16);
        float worst = 0.0f;
        int tested = 0;
        int inAir = 0;
        auto check = [&](glm::vec3 q, glm::vec3 expectedGradient) {
            const glm::vec3 g = finiteDifferenceGradient(q, o, h);
            const float err = maxAbs(g - expectedGradient);
            worst = std::max(worst, err);
            ++tested;
            EXPECT_LE(err, 2e-2f) << "q " << q.x << " " << q.y << " " << q.z << " grad " << g.x
                                  << " " << g.y << " " << g.z;
        };
        for (int i = 0; i < 4000; ++i) {
            const float delta = rng.uniform(0.003f, 0.02f);
            const float x = rng.uniform(hingeOf(o) + 0.05f, 0.9f);
            const float y = rng.uniform(-0.7f, 0.7f) * hw;
            // Across the hole's floor: empty above (w = -delta), material below
            // (w = +delta), one normal -z into the material, where the flap is far.
            const glm::vec3 above(x, y, floorZ + delta);
            if (shader::peelerFlapDistance(above, o) > 0.05f) {
                EXPECT_NEAR(signedDistance(above, o), -delta, 1e-5f);
                check(above, glm::vec3(0.0f, 0.0f, -1.0f));
            }
            const glm::vec3 below(x, y, floorZ - delta);
            EXPECT_NEAR(signedDistance(below, o), delta, 1e-5f);
            check(below, glm::vec3(0.0f, 0.0f, -1.0f));
            // Beside the hole: material at |y| = hw + delta, normal away from the hole.
            if (hw < 1.0f && x < 0.95f && x > hingeOf(o) + 0.05f) {
                const glm::vec3 beside(x, std::copysign(hw + delta, y), 1.0f - 0.5f * t);
                check(beside, glm::vec3(0.0f, std::copysign(1.0f, y), 0.0f));
            }
            // Inside the flap, delta under its underside; and, where the
            // underside faces air, just outside it (the air within 2t of the
            // flap is empty, so w changes sign on the flap's outline).
            const glm::vec3 p(x, y, floorZ + delta);
            const glm::vec3 q = shader::operatorForward(p, o);
            const glm::vec3 out = shader::operatorForward(glm::vec3(x, y, floorZ + 0.5f * t), o);
            const glm::vec3 normal = glm::normalize(q - out); // outward, across the layer
            if (flapPart(q, o) >= 0 && shader::peelerEndDistance(q, o) > 0.05f &&
                hw - std::abs(y) > 0.05f) {
                EXPECT_NEAR(signedDistance(q, o), delta, 1e-4f);
                check(q, -normal);
                const glm::vec3 air = q + 2.0f * delta * normal;
                if (air.z > 1.0f + 0.05f && flapPart(air, o) < 0 && 2.0f * delta < t) {
                    EXPECT_NEAR(signedDistance(air, o), -delta, 1e-4f);
                    check(air, -normal);
                    ++inAir;
                }
            }
        }
        EXPECT_GT(tested, 2000);
        if (angleOf(o) > 1.0f) {
            EXPECT_GT(inAir, 1000) << "the flap's underside faces the air";
        }
        recordWorst(c.name, worst);
    }
}

// Where the flap sweeps into untouched material (a thick layer's underside
// past x = 1) or lies on it (folded flat back), both have w > 0 and their
// pre-images are far apart: the baked map interpolated between them showed a
// lattice of samples from neither. A baked map's parameters carve a gap of two
// texels (b.y = a texel) out of the material there, so that valid points a
// texel apart have nearby pre-images. (Scene parameters, b.y = 0, carve none.)
TEST(Peeler, AGapPartsTheFlapFromMaterialItSweptInto) {
    const float texel = kTexel;
    for (const PeelerCase& c : peelerCases()) {
        SCOPED_TRACE(c.name);
        const OperatorParams o = sampled(c.o);
        EXPECT_FALSE(inGap(glm::vec3(1.2f, 0.3f, 0.9f), c.o)) << "no gap without b.y";
        Rng rng(18);
        float worst = 0.0f;
        int pairs = 0, carved = 0;
        for (int i = 0; i < 200000; ++i) {
            const glm::vec3 q =
                rng.inBox(glm::vec3(-2.5f, -1.0f, -1.0f), glm::vec3(2.0f, 1.0f, 3.5f));
            const glm::vec3 step =
                texel * glm::normalize(rng.inBox(glm::vec3(-1.0f), glm::vec3(1.0f)));
            const glm::vec4 a = shader::operatorBackward(q, o);
            const glm::vec4 b = shader::operatorBackward(q + step, o);
            if (inGap(q, o)) {
                ++carved;
                EXPECT_LE(a.w, 0.0f);
            }
            // Two valid regions meeting at a common cut face (the flap's side
            // and the hole's wall near the hinge) blend within half a texel of
            // it; the gap is for points deeper than that.
            if (a.w <= 0.5f * texel || b.w <= 0.5f * texel) continue;
            ++pairs;
            const float jump = maxAbs(glm::vec3(a) - glm::vec3(b));
            worst = std::max(worst, jump);
            EXPECT_LE(jump, 4.0f * texel) << "q " << q.x << " " << q.y << " " << q.z;
        }
        EXPECT_GT(pairs, 50000);
        if (std::string(c.name) == "thick") {
            EXPECT_GT(carved, 100) << "the thick flap sweeps into the material";
        }
        recordWorst(c.name, worst);
    }
}

// The map as the renderer bakes it (the shader's texel centres over the
// deformed bounds, with the gap its resolution sets) and samples it
// (trilinear, clamped to the edge texels): xyz the displacement, w.
class BakedMap {
public:
    BakedMap(const OperatorParams& o, glm::ivec3 res)
        : m_res(res), m_params(o), m_texels(std::size_t(res.x) * res.y * res.z) {
        const operators::LocalBox box = operators::deformedBounds(o, res);
        m_lo = glm::vec3(box.lo);
        m_texel = (glm::vec3(box.hi) - m_lo) / glm::vec3(res);
        m_params = operators::sampledParams(o, box, res);
        std::size_t i = 0;
        for (int z = 0; z < res.z; ++z)
            for (int y = 0; y < res.y; ++y)
                for (int x = 0; x < res.x; ++x, ++i) {
                    const glm::vec3 q = m_lo + (glm::vec3(x, y, z) + 0.5f) * m_texel;
                    const glm::vec4 b = shader::operatorBackward(q, m_params);
                    m_texels[i] = glm::vec4(glm::vec3(b) - q, b.w);
                }
    }
    const OperatorParams& params() const { return m_params; }
    glm::vec3 lo() const { return m_lo; }
    glm::vec3 hi() const { return m_lo + glm::vec3(m_res) * m_texel; }
    float texelDiagonal() const { return glm::length(m_texel); }
    glm::vec4 sample(glm::vec3 q) const {
        const glm::vec3 g = (q - m_lo) / m_texel - 0.5f;
        const glm::ivec3 i0(glm::floor(g));
        const glm::vec3 f = g - glm::vec3(i0);
        glm::vec4 sum(0.0f);
        for (int c = 0; c < 8; ++c) {
            const glm::ivec3 o(c & 1, (c >> 1) & 1, (c >> 2) & 1);
            const glm::ivec3 k = glm::clamp(i0 + o, glm::ivec3(0), m_res - 1);
            const float weight =
                (o.x ? f.x : 1 - f.x) * (o.y ? f.y : 1 - f.y) * (o.z ? f.z : 1 - f.z);
            sum +=
                weight * m_texels[std::size_t(k.x) + m_res.x * (k.y + std::size_t(m_res.y) * k.z)];
        }
        return sum;
    }

private:
    glm::ivec3 m_res;
    OperatorParams m_params;
    glm::vec3 m_lo{0.0f}, m_texel{0.0f};
    std::vector<glm::vec4> m_texels;
};

// Wherever the interpolated map keeps material (w > 0), its pre-image is
// within a few texels of the exact one: a texel cell whose corners hold
// pre-images far apart (the flap's and the identity) must be empty, or it
// shows tissue from neither. In peeler_head_surface.json the thick flap's
// underside crossed the hole's end face within a texel of it, and the gap's
// w jumped from 0 to the hole faces' distance at its outer edge: both showed
// as rows of bright dots of skull and skin in the air beside the flap (worst
// 12.6 texel diagonals at 64^3 before, 1.3 after).
// A fold past a right angle put the material just behind the hinge past the
// fold too: it took the straight part's coordinates and was carved as a gap
// with a pre-image far above the box ("extreme": 35 diagonals at 64^3).
TEST(Peeler, TheBakedMapKeepsOnlyPreimagesNearTheExactOnes) {
    std::vector<PeelerCase> cases = peelerCases();
    // peeler_head_surface.json: scale (110, 110, 40) mm, hinge -30, thickness
    // 36, radius 8, angle 140, width 70.
    cases.push_back({"scalpFlapScene", peelerParams(-30.0f / 55.0f, 36.0f / 20.0f, 8.0f / 20.0f,
                                                    140.0f * kPi / 180.0f, 35.0f / 55.0f)});
    for (const PeelerCase& c : cases) {
        for (const glm::ivec3 res : {glm::ivec3(32), glm::ivec3(64), glm::ivec3(96, 48, 64)}) {
            SCOPED_TRACE(std::string(c.name) + " at " + std::to_string(res.x) + "x" +
                         std::to_string(res.y) + "x" + std::to_string(res.z));
            const BakedMap map(c.o, res);
            Rng rng(23);
            float worst = 0.0f;
            int kept = 0;
            for (int i = 0; i < 100000; ++i) {
                const glm::vec3 q = rng.inBox(map.lo(), map.hi());
                const glm::vec4 m = map.sample(q);
                if (m.w <= 0.0f) continue;
                ++kept;
                const glm::vec3 exact(shader::operatorBackward(q, map.params()));
                const float off = glm::length(q + glm::vec3(m) - exact) / map.texelDiagonal();
                worst = std::max(worst, off);
                if (off > 3.0f) {
                    ADD_FAILURE() << "q " << q.x << " " << q.y << " " << q.z << ": " << off
                                  << " texel diagonals from the exact pre-image";
                    break;
                }
            }
            EXPECT_GT(kept, 10000) << "the test should sample kept material";
            recordWorst(c.name, worst);
        }
    }
}

} // namespace cutaway::test

// Manipulation operators (paper sections 3, 4.1; DESIGN.md section 4), written
// once for the GLSL bake shader and the C++ tests and bounds.
//
// CONTRACT (implemented by the functions below; see each for details):
//   Local frame: the operator's box V_T = [-1, 1]^3, tissue surface toward +z.
//   operatorForward(p, o)   T_F: where the material at p goes.
//   operatorBackward(q, o)  T_B of Eq. 2 in its CONTINUOUS form (holes filled):
//                           xyz = pre-image, w = signed distance (local units;
//                           the peeler's in units of the box's half z)
//                           to the cut surface: > 0 the point has a pre-image,
//                           <= 0 it lies in a cut or opening (empty). Operators
//                           without cuts return w = CW_NO_CUT.
//   operatorJacobian(q, o)  the analytic 3x3 Jacobian of the continuous T_B at q
//                           (column j = d T_B / d q_j), for normals: the
//                           gradient of f(T_B(q)) is transpose(J) * grad f.
// Points outside [-1, 1]^3 that no operator material reaches map to themselves
// (the retractor continues its surface opening above z = 1 so that a map
// baked over the box plus padding stays continuous across its top face).
// Each operator's block below lists its parameter ranges, the box faces that
// stay fixed, and how its signed distance is defined.
#ifndef CUTAWAY_OPERATORS_H
#define CUTAWAY_OPERATORS_H

#include "shared/glsl_cpp.h"

#define CW_OP_PEELER 0
#define CW_OP_RETRACTOR 1
#define CW_OP_PLIERS 2
#define CW_OP_DILATOR 3
#define CW_NO_CUT 1000.0f

// max |g'(u)| of the pliers' profile g(u) = (1 - u^2)^3, at u = 1/sqrt(5):
// 96 / (25 sqrt(5)).
#define CW_PLIERS_MAX_SLOPE 1.7173002f
// Safeguarded Newton steps of the pliers' backward map (see pliersBackward).
#define CW_PLIERS_ITERATIONS 12

CW_NAMESPACE_BEGIN

// Parameters in local units (the box is 2 wide); meaning per type:
//   peeler:    a = (hinge x, layer thickness, bend radius, fold angle in radians)
//              b = (half width of the peel along y, gap, box half x, box half y),
//              all in units of the box's half z (see PEELER below)
//   retractor: a = (half length of the incision along y, depth from the surface,
//                   half opening width at the surface centre, 0)
//   pliers:    a = (grasp centre xyz, radius of influence)
//              b = (displacement xyz, 0)
//   dilator:   a = (inner radius, magnification, shape: 0 spherical / 1 cylindrical about z, 0)
struct OperatorParams {
    vec4 a;
    vec4 b;
    vec4 kind; // x: CW_OP_* as a float
};

// Distance from q to the axis-aligned box [lo, hi] (0 inside); lo == hi on an
// axis gives a face rectangle.
CW_FUNC float distanceToBox(vec3 q, vec3 lo, vec3 hi) {
    return length(max(max(lo - q, q - hi), vec3(0.0f)));
}

// ---------------------------------------------------------------------------
// PEELER: a bend (Barr 1984, "Global and local deformations of solid
// primitives"). A fold is rigid, so the peeler works in a frame of equal
// units along its axes: local x and y times the box's aspect, X = b.z and
// Y = b.w (its half extents over its half z), so that the box is [-X, X] x
// [-Y, Y] x [-1, 1] and one unit is the box's half height along every axis.
// The functions below take and give points of that frame; operatorForward,
// operatorBackward and operatorJacobian convert (peelerToIso). In the unit
// box's own units a box longer than high would fold its layer into an
// ellipse, thicker by X and shorter by 1 / X once turned upright.
// The layer x in (h, X], |y| < halfWidth, depth e = 1 - z in
// [0, t] is cut free along its underside, its sides and its end (x = 1) and
// wrapped around a cylinder whose axis is parallel to y through
// c = (h, *, 1 + R): the layer point at arc length s = x - h goes to angle
// phi = s / R (the direction from c at angle phi is n(phi) = (sin phi, 0,
// -cos phi), so the hinge point (h, 1) is on the cylinder) at radius R + e;
// beyond phi = theta it continues straight along tau(theta) = (cos theta, 0,
// sin theta). The skin (e = 0) ends up facing the cylinder, the underside
// (e = t) outward. Arc length is kept on the skin; deeper material stretches
// by (R + e) / R around the bend.
//   a.x  h      hinge, in [-X, X); the layer beyond it is lifted
//   a.y  t      layer thickness, in (0, 2): below 2 the face z = -1 is untouched
//   a.z  R      bend radius, > 0 (>= 1e-3 keeps the Jacobian well scaled)
//   a.w  theta  fold angle, in [0, pi]; 0 is exactly the identity. Up to pi
//               the flap overlaps neither itself nor the untouched material in
//               the box (beyond pi its straight part would dive into it)
//   b.x  halfWidth  half width along y, in (0, Y]; values above Y act as Y
//   b.y  gap  half the gap carved where the flap meets untouched material:
//             set by a bake to a texel of its map (operators::sampledParams), 0 in a
//             scene's parameters (the analytic map is never interpolated)
//   b.z  X      the box's half extent along x over its half extent along z, > 0
//   b.w  Y      the same along y, > 0
// Faces that stay fixed: x = -X, z = -1, and |y| = Y when halfWidth < Y. The
// top z = 1 and the end x = X are cuts (the flap leaves them). A thick layer
// ((X - h)^2 + R^2 < (R + t)^2) bends its underside through the material past
// x = X below z = 1, and for small theta the lower edge of the flap's end
// swings up to about t * theta past x = X: where the flap is, it wins, and a
// baked map carves a gap in the material around it (b.y, see below).
//
// Backward map (continuous version): on the flap, its pre-image; elsewhere
// the identity, which fills the hole the layer left (so Jacobians there are I),
// except at empty points next to the flap, which continue its pre-image.
// Signed distance w:
//   flap:     + min(distance to its underside, its sides, its end face). The
//             skin (e = 0) is not a cut, and neither is the hinge.
//   hole:     - min(distance to the hole's bottom, sides, end and hinge
//             planes, distance to the flap): the lifted region x in (h, X],
//             |y| < halfWidth, z in [1 - t, 1], where the flap is not. Where
//             the flap passes within 2 gap of those faces, the material it
//             carves there (below) does not count (peelerClearance).
//   air:      z > 1 and not on the flap. It maps to itself; within 2t of the
//             flap it counts as empty (w = |d - t| - t < 0, d = distance to the
//             flap) so that w changes sign at every face where the pre-image
//             jumps from the flap's to the identity, and a baked map
//             interpolated across the flap's outline sees an edge rather than
//             a smear. Farther away it is like material (w > 0): anything there
//             is not the operator's business (Eq. 3).
//   material: + distance to the cut faces (the hole's bottom, sides and end),
//             except within 2 gap of a flap that swept into it or lies on it
//             (its pre-image there 2 gap or more from the identity): empty,
//             as the air within 2t, with the flap's pre-image continued up to
//             gap. Without the gap, the map interpolated between the flap and
//             that material, both with w > 0, showed a lattice of samples from
//             neither. The gap is a cut: beyond it w is at most d - 2 gap.
// ---------------------------------------------------------------------------

CW_FUNC vec3 peelerRadial(float phi) {
    return vec3(sin(phi), 0.0f, -cos(phi));
}

CW_FUNC vec3 peelerTangent(float phi) {
    return vec3(cos(phi), 0.0f, sin(phi));
}

// The box's end along x, X.
CW_FUNC float peelerEnd(OperatorParams o) {
    return o.b.z;
}

// The half width actually lifted: the box ends at |y| = Y.
CW_FUNC float peelerHalfWidth(OperatorParams o) {
    return min(o.b.x, o.b.w);
}

// Local (unit box) coordinates to the peeler's frame of equal units, and back.
CW_FUNC vec3 peelerToIso(vec3 p, OperatorParams o) {
    return vec3(p.x * o.b.z, p.y * o.b.w, p.z);
}

CW_FUNC vec3 peelerFromIso(vec3 q, OperatorParams o) {
    return vec3(q.x / o.b.z, q.y / o.b.w, q.z);
}

// Angle at which the flap ends on its bend (the fold angle if the flap is
// longer than the bend), and the length of its straight part.
CW_FUNC vec2 peelerFlapEnd(OperatorParams o) {
    float flapLength = peelerEnd(o) - o.a.x;
    float phiEnd = min(o.a.w, flapLength / o.a.z);
    return vec2(phiEnd, max(flapLength - o.a.z * phiEnd, 0.0f));
}

CW_FUNC vec3 peelerForward(vec3 p, OperatorParams o) {
    float h = o.a.x;
    float t = o.a.y;
    float radius = o.a.z;
    float s = p.x - h;
    float e = 1.0f - p.z;
    bool lifted =
        s > 0.0f && p.x <= peelerEnd(o) && abs(p.y) < peelerHalfWidth(o) && e >= 0.0f && e <= t;
    if (!lifted) return p;
    float phi = min(s / radius, o.a.w);
    vec3 axis = vec3(h, 0.0f, 1.0f + radius);
    vec3 q = axis + (radius + e) * peelerRadial(phi) + (s - radius * phi) * peelerTangent(phi);
    return vec3(q.x, p.y, q.z);
}

// Distances in the xz-plane from q to the flap's cross section: x to its
// bend (an annular sector around the axis), y to its straight part (a
// rectangle; meaningless when it has none).
CW_FUNC vec2 peelerSectionDistances(vec3 q, OperatorParams o) {
    float radius = o.a.z;
    float outer = radius + o.a.y;
    vec2 end = peelerFlapEnd(o);
    vec3 v = vec3(q.x - o.a.x, 0.0f, q.z - (1.0f + radius));
    float r = length(v);
    float phi = atan(v.x, -v.z);
    float sector;
    if (phi >= 0.0f && phi <= end.x) {
        sector = max(max(radius - r, r - outer), 0.0f);
    } else { // nearest point on one of the two radial edges
        vec3 n0 = peelerRadial(0.0f);
        vec3 n1 = peelerRadial(end.x);
        sector = min(length(v - clamp(dot(v, n0), radius, outer) * n0),
                     length(v - clamp(dot(v, n1), radius, outer) * n1));
    }
    float a = dot(v, peelerRadial(o.a.w));
    float b = dot(v, peelerTangent(o.a.w));
    float straight =
        length(vec2(max(max(radius - a, a - outer), 0.0f), max(max(-b, b - end.y), 0.0f)));
    return vec2(sector, straight);
}

// Bend coordinates of q: (s, e, part) with part 0 on the flap's bend, 1 on
// its straight part; off the flap -2 (bend coordinates) or -1 (straight-part
// coordinates), and s < 0 where they mean nothing (behind the hinge).
CW_FUNC vec3 peelerFlapCoords(vec3 q, OperatorParams o) {
    float radius = o.a.z;
    float theta = o.a.w;
    vec3 v = vec3(q.x - o.a.x, 0.0f, q.z - (1.0f + radius));
    float along = dot(v, peelerTangent(theta)); // > 0: past the fold angle
    float s;
    float e;
    float part;
    // Past the fold angle and nearer the straight part than the bend: a fold
    // beyond a right angle also puts the material behind the hinge past it,
    // which meets the flap at the hinge (bend coordinates, s < 0); with the
    // straight part's it was carved as a gap with a pre-image far above it.
    bool straight = along > 0.0f && peelerFlapEnd(o).y > 0.0f;
    if (straight) {
        vec2 parts = peelerSectionDistances(q, o);
        straight = parts.y <= parts.x;
    }
    if (straight) {
        s = radius * theta + along;
        e = dot(v, peelerRadial(theta)) - radius;
        part = 1.0f;
    } else {
        float phi = atan(v.x, -v.z); // from -z toward +x, in (-pi, pi]
        s = phi < 0.0f ? -1.0f : radius * phi;
        e = length(v) - radius;
        part = 0.0f;
    }
    bool on = s >= 0.0f && s <= peelerEnd(o) - o.a.x && e >= 0.0f && e <= o.a.y &&
              abs(q.y) < peelerHalfWidth(o);
    return vec3(s, e, on ? part : part - 2.0f);
}

// Distance in the xz-plane from q to the flap's end face (a segment).
CW_FUNC float peelerEndDistance(vec3 q, OperatorParams o) {
    float radius = o.a.z;
    vec2 end = peelerFlapEnd(o);
    vec3 v = vec3(q.x - o.a.x, 0.0f, q.z - (1.0f + radius));
    vec3 n = peelerRadial(end.x);
    vec3 foot = clamp(dot(v, n), radius, radius + o.a.y) * n + end.y * peelerTangent(end.x);
    return length(v - foot);
}

// Distance from q (outside the flap) to the flap: in the xz-plane to its cross
// section, then combined with how far |y| is beyond the half width.
CW_FUNC float peelerFlapDistance(vec3 q, OperatorParams o) {
    vec2 parts = peelerSectionDistances(q, o);
    float d = peelerFlapEnd(o).y > 0.0f ? min(parts.x, parts.y) : parts.x;
    return length(vec2(d, max(abs(q.y) - peelerHalfWidth(o), 0.0f)));
}

// Distance to the cut faces of the hole: its bottom, its sides, its end.
CW_FUNC float peelerHoleFaceDistance(vec3 q, OperatorParams o) {
    float h = o.a.x;
    float floorZ = 1.0f - o.a.y;
    float hw = peelerHalfWidth(o);
    float x1 = peelerEnd(o);
    float bottom = distanceToBox(q, vec3(h, -hw, floorZ), vec3(x1, hw, floorZ));
    float side = distanceToBox(vec3(q.x, abs(q.y), q.z), vec3(h, hw, floorZ), vec3(x1, hw, 1.0f));
    float endFace = distanceToBox(q, vec3(x1, -hw, floorZ), vec3(x1, hw, 1.0f));
    return min(min(bottom, side), endFace);
}

// Whether q lies in the hole the flap left.
CW_FUNC bool peelerInHole(vec3 q, OperatorParams o) {
    float hw = peelerHalfWidth(o);
    return q.x > o.a.x && q.x <= peelerEnd(o) && abs(q.y) < hw && q.z >= 1.0f - o.a.y &&
           q.z <= 1.0f;
}

// Distance from q, in the hole or the air, to what the operator leaves alone:
// the hole's floor, sides, end and hinge planes, or the material outside the
// hole's open top (the half-space z <= 1 around it).
CW_FUNC float peelerUntouchedDistance(vec3 q, OperatorParams o) {
    float h = o.a.x;
    float hw = peelerHalfWidth(o);
    float x1 = peelerEnd(o);
    bool overHole = q.x > h && q.x < x1 && abs(q.y) < hw;
    float rim = overHole ? min(min(q.x - h, x1 - q.x), hw - abs(q.y)) : 0.0f;
    if (q.z > 1.0f) return length(vec2(q.z - 1.0f, rim));
    return min(rim, q.z - (1.0f - o.a.y));
}

// The flap's pre-image continued to q (bend coordinates f, out of bounds).
CW_FUNC vec3 peelerContinued(vec3 q, vec3 f, OperatorParams o) {
    return vec3(o.a.x + f.x, q.y, 1.0f - f.y);
}

// Whether the flap carves a gap in untouched material near q: where its
// pre-image continued to q is a gap or more from q (so not at the hinge,
// where the two meet continuously).
CW_FUNC bool peelerGapCarves(vec3 q, vec3 f, OperatorParams o) {
    return f.x >= 0.0f && length(peelerContinued(q, f, o) - q) > 2.0f * o.b.y;
}

// Whether untouched material at q, at distance d from the flap, lies in the
// gap carved around a flap that swept into it, lies on it, or passes the
// hole's wall beside it (where both sides have w > 0 up to the wall): nearer
// the flap than the gap, where the flap carves one.
CW_FUNC bool peelerInGap(vec3 q, vec3 f, float d, OperatorParams o) {
    return d < 2.0f * o.b.y && peelerGapCarves(q, f, o);
}

// Distance from q, in the hole or the air at distance d from the flap, to the
// material the operator leaves in place. Material within 2 gap of the flap is
// carved (peelerInGap), so where that holds at q too, kept material is at
// least 2 gap - d away: a thick flap whose underside crosses the hole's end
// face passes within a texel of it, and with the face's distance alone no
// texel between them was clearly empty, so the map blended the flap's
// pre-image with the identity there (bright dots of skull in the air).
CW_FUNC float peelerClearance(vec3 q, vec3 f, float d, OperatorParams o) {
    float untouched = peelerUntouchedDistance(q, o);
    return peelerInGap(q, f, d, o) ? max(untouched, 2.0f * o.b.y - d) : untouched;
}

// Whether q, off the flap with bend coordinates f and at distance d from it,
// takes the flap's pre-image continued (see peelerBackward): in the hole or
// the air, nearer the flap than what the operator leaves alone, and in the
// air within t of the flap; in the material, the near half of the gap.
CW_FUNC bool peelerContinues(vec3 q, vec3 f, float d, OperatorParams o) {
    if (f.x < 0.0f) return false;
    if (!peelerInHole(q, o)) {
        if (q.z <= 1.0f) return d < o.b.y && peelerInGap(q, f, d, o); // material
        if (d >= o.a.y) return false;                                 // air beyond t
    }
    return d < peelerClearance(q, f, d, o);
}

CW_FUNC vec4 peelerBackward(vec3 q, OperatorParams o) {
    float h = o.a.x;
    float t = o.a.y;
    float hw = peelerHalfWidth(o);
    vec3 f = peelerFlapCoords(q, o);
    if (f.z >= 0.0f) {
        float w = min(min(t - f.y, hw - abs(q.y)), peelerEndDistance(q, o));
        return vec4(h + f.x, q.y, 1.0f - f.y, w);
    }
    // Empty points next to the flap take its pre-image continued past its
    // faces (bend coordinates out of bounds), the others the identity: a baked
    // map interpolated across a cut face then blends two nearby pre-images,
    // not the flap's with one a flap's length away, which would sample the
    // wrong tissue on the cut face in a band a texel wide. The switch lies
    // where w is most negative: halfway between the flap and the untouched
    // material (where w jumps, at the material's top, the map must not), or
    // halfway across the empty shell in the air.
    bool inHole = peelerInHole(q, o);
    float w = inHole ? 0.0f : peelerHoleFaceDistance(q, o);
    bool material = !inHole && q.z <= 1.0f;
    if (material && o.b.y <= 0.0f) return vec4(q, w);
    float d = peelerFlapDistance(q, o);
    vec3 p = peelerContinues(q, f, d, o) ? peelerContinued(q, f, o) : q;
    if (material) {
        // The gap is a cut: beyond it w is also at most the distance to it,
        // d - 2 gap. Had w jumped there from 0 to the hole faces' distance,
        // a texel cell spanning the gap's outer half (one is wider than a
        // gap along its diagonal) would blend the flap's pre-image continued
        // with the identity at w > 0: dots of skin in the air.
        if (peelerGapCarves(q, f, o)) w = min(w, abs(d - o.b.y) - o.b.y);
        return vec4(p, w);
    }
    if (inHole) return vec4(p, -min(peelerClearance(q, f, d, o), d));
    return vec4(p, min(w, abs(d - t) - t)); // air
}

CW_FUNC mat3 peelerJacobian(vec3 q, OperatorParams o) {
    vec3 f = peelerFlapCoords(q, o);
    if (f.z < 0.0f && !peelerContinues(q, f, peelerFlapDistance(q, o), o)) return mat3(1.0f);
    // Straight part (on the flap or continued): a rigid motion, x from
    // tau(theta), z from -n(theta).
    if (f.z > 0.5f || f.z == -1.0f) {
        float c = cos(o.a.w);
        float s = sin(o.a.w);
        return mat3(vec3(c, 0.0f, -s), vec3(0.0f, 1.0f, 0.0f), vec3(s, 0.0f, c));
    }
    // Bend: pre-image (h + R phi, y, 1 - (|v| - R)), phi = atan(v.x, -v.z).
    float radius = o.a.z;
    vec3 v = vec3(q.x - o.a.x, 0.0f, q.z - (1.0f + radius));
    float r2 = dot(v, v);
    float r = sqrt(r2);
    return mat3(vec3(-radius * v.z / r2, 0.0f, -v.x / r), vec3(0.0f, 1.0f, 0.0f),
                vec3(radius * v.x / r2, 0.0f, -v.z / r));
}

// ---------------------------------------------------------------------------
// RETRACTOR: a split. The incision is the plane x = 0 for |y| < L, from the
// surface z = 1 down to z = 1 - D. Its sides are spread apart by the half
// opening w(y, z) = W bump(y / L) ramp((z - (1 - D)) / D), bump(u) = (1 -
// u^2)^2 for |u| < 1, ramp = smoothstep (0 at the bottom, 1 at and above the
// surface); both are C1, so w and the map are C1 across the incision's ends
// and bottom. Forward: x' = sign(x) (w + |x| (1 - w)) for |x| <= 1 (y, z
// unchanged): the displacement falls off linearly to 0 at |x| = 1.
//   a.x  L  half length along y, in (0, 1]: |y| = 1 stays fixed
//   a.y  D  depth from the surface, in (0, 2]: z = -1 stays fixed
//   a.z  W  half opening at the surface centre, in [0, 1): the map is
//           invertible (dx'/d|x| = 1 - w > 0); 0 is the identity
// Faces that stay fixed: |x| = 1, |y| = 1, z = -1 (the deformed box is the box).
// Above the surface (outside the box) the map continues with the surface's
// opening, so it stays continuous across z = 1.
//
// Backward: |x| = (|x'| - w) / (1 - w) where |x'| >= w; the opening |x'| < w
// is empty and filled continuously with x = 0 (the incision plane), where the
// Jacobian is finite but has a zero first row. Signed distance: inside the
// incision's footprint (|y| < L, z > 1 - D) the first-order distance to the
// wall |x'| = w(y, z), (|x'| - w) / sqrt(1 + |grad w|^2) (exact on the wall,
// unit gradient there); outside it the distance to the incision's edge,
// sqrt(x'^2 + d_yz^2), which matches at the footprint's boundary where w and
// grad w vanish.
// ---------------------------------------------------------------------------

// (w, dw/dy, dw/dz) at (y, z).
CW_FUNC vec3 retractorOpening(float y, float z, OperatorParams o) {
    float halfLength = o.a.x;
    float depth = o.a.y;
    float u = y / halfLength;
    float k = 1.0f - u * u;
    float bump = abs(u) < 1.0f ? k * k : 0.0f;
    float bumpSlope = abs(u) < 1.0f ? -4.0f * u * k : 0.0f;
    float v = clamp((z - (1.0f - depth)) / depth, 0.0f, 1.0f);
    float ramp = v * v * (3.0f - 2.0f * v);
    float rampSlope = 6.0f * v * (1.0f - v);
    float width = o.a.z;
    return vec3(width * bump * ramp, width * bumpSlope * ramp / halfLength,
                width * bump * rampSlope / depth);
}

CW_FUNC vec3 retractorForward(vec3 p, OperatorParams o) {
    if (abs(p.x) > 1.0f) return p;
    float w = retractorOpening(p.y, p.z, o).x;
    return vec3(sign(p.x) * (w + abs(p.x) * (1.0f - w)), p.y, p.z);
}

CW_FUNC vec4 retractorBackward(vec3 q, OperatorParams o) {
    vec3 w = retractorOpening(q.y, q.z, o);
    float ax = abs(q.x);
    float x = ax > 1.0f ? q.x : sign(q.x) * max(ax - w.x, 0.0f) / (1.0f - w.x);
    float outsideY = max(abs(q.y) - o.a.x, 0.0f);
    float belowZ = max((1.0f - o.a.y) - q.z, 0.0f);
    float d;
    if (outsideY > 0.0f || belowZ > 0.0f)
        d = length(vec3(q.x, outsideY, belowZ));
    else
        d = (ax - w.x) / sqrt(1.0f + w.y * w.y + w.z * w.z);
    return vec4(x, q.y, q.z, d);
}

CW_FUNC mat3 retractorJacobian(vec3 q, OperatorParams o) {
    vec3 w = retractorOpening(q.y, q.z, o);
    float ax = abs(q.x);
    if (ax > 1.0f) return mat3(1.0f);
    if (ax < w.x) return mat3(vec3(0.0f), vec3(0.0f, 1.0f, 0.0f), vec3(0.0f, 0.0f, 1.0f));
    float inv = 1.0f / (1.0f - w.x);
    float dxdw = sign(q.x) * (ax - 1.0f) * inv * inv; // d x / d w
    return mat3(vec3(inv, 0.0f, 0.0f), vec3(dxdw * w.y, 1.0f, 0.0f), vec3(dxdw * w.z, 0.0f, 1.0f));
}

// ---------------------------------------------------------------------------
// PLIERS: p' = p + d g(|p - c| / r), g(u) = (1 - u^2)^3 for u < 1, else 0
// (g(0) = 1, C2 at u = 1, compact support: the ball |p - c| < r).
//   a.xyz  c  grasp centre
//   a.w    r  radius of influence, > 0; with |c_i| + r <= 1 on every axis the
//             ball fits in the box and all six faces stay fixed
//   b.xyz  d  displacement of the grasped point; d = 0 is the identity
// Invertible while k = |d| max|g'| / r < 1 (pliersContraction, max|g'| =
// 96 / (25 sqrt 5) ~ 1.7173): then |T_F(p1) - T_F(p2)| >= (1 - k) |p1 - p2|,
// and T_F maps the ball onto itself (it moves no point out of it).
//
// Backward: the pre-image is q - lambda d with lambda = g(|q - lambda d - c| / r)
// in [0, 1], a scalar equation whose left minus right side grows with slope
// >= 1 - k > 0: a bracketed Newton iteration (bisection where a step would
// leave the bracket), CW_PLIERS_ITERATIONS steps, no early exit. Continuous
// everywhere, no cut: w = CW_NO_CUT. Jacobian: the inverse of I + d grad(g)^T
// at the pre-image, by Sherman-Morrison.
// ---------------------------------------------------------------------------

// g as a function of u^2, and g'(u) / u (finite at u = 0).
CW_FUNC float pliersProfile(float u2) {
    float k = 1.0f - u2;
    return u2 < 1.0f ? k * k * k : 0.0f;
}

CW_FUNC float pliersProfileSlopeOverU(float u2) {
    float k = 1.0f - u2;
    return u2 < 1.0f ? -6.0f * k * k : 0.0f;
}

// The contraction factor |d| max|g'| / r: the backward map is defined and
// found while it is < 1 (the scene validator asks for some margin).
CW_FUNC float pliersContraction(OperatorParams o) {
    return length(vec3(o.b)) * CW_PLIERS_MAX_SLOPE / o.a.w;
}

CW_FUNC vec3 pliersForward(vec3 p, OperatorParams o) {
    vec3 v = p - vec3(o.a);
    return p + vec3(o.b) * pliersProfile(dot(v, v) / (o.a.w * o.a.w));
}

CW_FUNC vec4 pliersBackward(vec3 q, OperatorParams o) {
    vec3 d = vec3(o.b);
    float invR2 = 1.0f / (o.a.w * o.a.w);
    vec3 v0 = q - vec3(o.a);
    float lambda = pliersProfile(dot(v0, v0) * invR2); // one fixed-point step from 0
    float lo = 0.0f;
    float hi = 1.0f;
    for (int i = 0; i < CW_PLIERS_ITERATIONS; i++) {
        vec3 v = v0 - lambda * d;
        float u2 = dot(v, v) * invR2;
        float residual = lambda - pliersProfile(u2);
        float slope = 1.0f + pliersProfileSlopeOverU(u2) * dot(v, d) * invR2;
        if (residual < 0.0f)
            lo = lambda;
        else
            hi = lambda;
        float next = lambda - residual / slope;
        lambda = (next >= lo && next <= hi) ? next : 0.5f * (lo + hi);
    }
    return vec4(q - lambda * d, CW_NO_CUT);
}

CW_FUNC mat3 pliersJacobian(vec3 q, OperatorParams o) {
    vec3 p = vec3(pliersBackward(q, o));
    vec3 v = p - vec3(o.a);
    float invR2 = 1.0f / (o.a.w * o.a.w);
    vec3 gradG = pliersProfileSlopeOverU(dot(v, v) * invR2) * invR2 * v;
    vec3 d = vec3(o.b);
    return mat3(1.0f) - outerProduct(d, gradG) / (1.0f + dot(gradG, d));
}

// ---------------------------------------------------------------------------
// DILATOR: a volumetric magic lens. Radial profile r' = F(r) (r = |p|, or
// |p.xy| for the cylinder about z, whose z stays unchanged): F(r) = m r for
// r <= rho, F(r) = r for r >= 1, and in between the rational quadratic
// Hermite interpolant of Gregory & Delbourgo (IMA J. Numer. Anal. 2, 1982)
// from (rho, m rho, slope m) to (1, 1, slope 1). Unlike the cubic Hermite it is
// monotone for ANY positive end slopes and increasing data, so F is C1 and
// strictly increasing whenever m rho < 1, and its inverse is a quadratic
// equation solved in closed form.
//   a.x  rho    inner radius, uniformly magnified, in [0, 1)
//   a.y  m      magnification, > 0, with m rho < 1 (F stays increasing);
//               1 is the identity; below 1 shrinks. The shell [rho, 1] is
//               squeezed into [m rho, 1]: where m exceeds the mean slope
//               (1 - m rho) / (1 - rho) a lot, F' dips far below it (min F'
//               0.30 for m = 2, rho = 0.3; 0.012 for m = 2.1, rho = 0.45;
//               0.003 for m = 10, rho = 0.09), and T_B's Jacobian is 1 / F'.
//   a.z  shape  0 sphere, 1 cylinder about the local z axis
// Faces that stay fixed: all six for the sphere (it ends at radius 1); |x| = 1
// and |y| = 1 for the cylinder, which runs through z = +-1. No cut: w =
// CW_NO_CUT.
// ---------------------------------------------------------------------------

CW_FUNC float dilatorProfile(float r, float rho, float m) {
    if (r <= rho) return m * r;
    if (r >= 1.0f) return r;
    float span = 1.0f - rho;
    float secant = (1.0f - m * rho) / span;
    float s = (r - rho) / span;
    float st = s * (1.0f - s);
    return m * rho + (1.0f - m * rho) * (secant * s * s + m * st) /
                         (secant + (m + 1.0f - 2.0f * secant) * st);
}

CW_FUNC float dilatorProfileSlope(float r, float rho, float m) {
    if (r <= rho) return m;
    if (r >= 1.0f) return 1.0f;
    float span = 1.0f - rho;
    float secant = (1.0f - m * rho) / span;
    float s = (r - rho) / span;
    float st = s * (1.0f - s);
    float den = secant + (m + 1.0f - 2.0f * secant) * st;
    float num = s * s + 2.0f * secant * st + m * (1.0f - s) * (1.0f - s);
    return secant * secant * num / (den * den);
}

CW_FUNC float dilatorProfileInverse(float y, float rho, float m) {
    if (y <= m * rho) return y / m;
    if (y >= 1.0f) return y;
    float span = 1.0f - rho;
    float secant = (1.0f - m * rho) / span;
    float k = m + 1.0f - 2.0f * secant;
    float f = (y - m * rho) / (1.0f - m * rho);
    // secant s^2 + m s (1 - s) = f (secant + k s (1 - s)), i.e. A s^2 + B s + C = 0
    // with A + B = secant > 0, C <= 0: the root in [0, 1] without cancellation.
    float qa = secant - m + f * k;
    float qb = m - f * k;
    float qc = -f * secant;
    float s = -2.0f * qc / (qb + sqrt(max(qb * qb - 4.0f * qa * qc, 0.0f)));
    return rho + span * s;
}

// The part of q the profile acts on: all of it, or its xy for the cylinder.
CW_FUNC vec3 dilatorRadialPart(vec3 q, OperatorParams o) {
    return o.a.z > 0.5f ? vec3(q.x, q.y, 0.0f) : q;
}

CW_FUNC vec3 dilatorForward(vec3 p, OperatorParams o) {
    vec3 radial = dilatorRadialPart(p, o);
    float r = length(radial);
    float scale = r > o.a.x ? dilatorProfile(r, o.a.x, o.a.y) / r : o.a.y;
    return p + (scale - 1.0f) * radial;
}

CW_FUNC vec4 dilatorBackward(vec3 q, OperatorParams o) {
    vec3 radial = dilatorRadialPart(q, o);
    float y = length(radial);
    float rho = o.a.x;
    float m = o.a.y;
    float scale = y > m * rho ? dilatorProfileInverse(y, rho, m) / y : 1.0f / m;
    return vec4(q + (scale - 1.0f) * radial, CW_NO_CUT);
}

// Radially 1 / F'(r), tangentially r / F(r) (and 1 along z for the cylinder).
CW_FUNC mat3 dilatorJacobian(vec3 q, OperatorParams o) {
    vec3 radial = dilatorRadialPart(q, o);
    float y = length(radial);
    float rho = o.a.x;
    float m = o.a.y;
    if (y >= 1.0f) return mat3(1.0f);
    float tangential = 1.0f / m;
    float normal = 1.0f / m;
    vec3 n = vec3(0.0f);
    if (y > m * rho) {
        float r = dilatorProfileInverse(y, rho, m);
        tangential = r / y;
        normal = 1.0f / dilatorProfileSlope(r, rho, m);
        n = radial / y;
    }
    mat3 j = tangential * mat3(1.0f) + (normal - tangential) * outerProduct(n, n);
    if (o.a.z > 0.5f) j[2] = vec3(0.0f, 0.0f, 1.0f);
    return j;
}

// ---------------------------------------------------------------------------
// Dispatch on int(o.kind.x).
// ---------------------------------------------------------------------------

CW_FUNC int operatorKind(OperatorParams o) {
    return int(o.kind.x + 0.5f);
}

// True where the parameters move nothing: peeler theta = 0 (or nothing to
// lift), retractor W = 0, pliers d = 0 (or r = 0), dilator m = 1, an unknown
// kind. The maps then return their argument exactly, J = I, w = CW_NO_CUT.
CW_FUNC bool operatorIsIdentity(OperatorParams o) {
    int kind = operatorKind(o);
    if (kind == CW_OP_PEELER)
        return !(o.a.w > 0.0f && o.a.y > 0.0f && o.b.x > 0.0f && o.a.x < o.b.z);
    if (kind == CW_OP_RETRACTOR) return !(o.a.z > 0.0f && o.a.x > 0.0f && o.a.y > 0.0f);
    if (kind == CW_OP_PLIERS) return !(dot(vec3(o.b), vec3(o.b)) > 0.0f && o.a.w > 0.0f);
    if (kind == CW_OP_DILATOR) return o.a.y == 1.0f;
    return true;
}

// The ranges documented above, in which the maps are invertible and the
// listed faces stay fixed (identity settings included). The scene validator
// may use it as a last check; its own messages name the offending key.
CW_FUNC bool operatorParamsValid(OperatorParams o) {
    int kind = operatorKind(o);
    if (kind == CW_OP_PEELER)
        return o.b.z > 0.0f && o.b.w > 0.0f && o.a.x >= -o.b.z && o.a.x < o.b.z && o.a.y > 0.0f &&
               o.a.y < 2.0f && o.a.z > 0.0f && o.a.w >= 0.0f && o.a.w <= 3.14159265f &&
               o.b.x > 0.0f;
    if (kind == CW_OP_RETRACTOR)
        return o.a.x > 0.0f && o.a.x <= 1.0f && o.a.y > 0.0f && o.a.y <= 2.0f && o.a.z >= 0.0f &&
               o.a.z < 1.0f;
    if (kind == CW_OP_PLIERS) {
        vec3 extent = abs(vec3(o.a)) + vec3(o.a.w);
        return o.a.w > 0.0f && max(max(extent.x, extent.y), extent.z) <= 1.0f &&
               pliersContraction(o) < 1.0f;
    }
    if (kind == CW_OP_DILATOR)
        return o.a.x >= 0.0f && o.a.x < 1.0f && o.a.y > 0.0f && o.a.y * o.a.x < 1.0f;
    return false;
}

CW_FUNC vec3 operatorForward(vec3 p, OperatorParams o) {
    if (operatorIsIdentity(o)) return p;
    int kind = operatorKind(o);
    if (kind == CW_OP_PEELER) return peelerFromIso(peelerForward(peelerToIso(p, o), o), o);
    if (kind == CW_OP_RETRACTOR) return retractorForward(p, o);
    if (kind == CW_OP_PLIERS) return pliersForward(p, o);
    return dilatorForward(p, o);
}

CW_FUNC vec4 operatorBackward(vec3 q, OperatorParams o) {
    if (operatorIsIdentity(o)) return vec4(q, CW_NO_CUT);
    int kind = operatorKind(o);
    if (kind == CW_OP_PEELER) {
        vec4 b = peelerBackward(peelerToIso(q, o), o);
        return vec4(peelerFromIso(vec3(b), o), b.w);
    }
    if (kind == CW_OP_RETRACTOR) return retractorBackward(q, o);
    if (kind == CW_OP_PLIERS) return pliersBackward(q, o);
    return dilatorBackward(q, o);
}

CW_FUNC mat3 operatorJacobian(vec3 q, OperatorParams o) {
    if (operatorIsIdentity(o)) return mat3(1.0f);
    int kind = operatorKind(o);
    if (kind == CW_OP_PEELER) { // S^-1 J S, S = diag(X, Y, 1)
        mat3 s = mat3(vec3(o.b.z, 0.0f, 0.0f), vec3(0.0f, o.b.w, 0.0f), vec3(0.0f, 0.0f, 1.0f));
        mat3 sInverse = mat3(vec3(1.0f / o.b.z, 0.0f, 0.0f), vec3(0.0f, 1.0f / o.b.w, 0.0f),
                             vec3(0.0f, 0.0f, 1.0f));
        return sInverse * peelerJacobian(peelerToIso(q, o), o) * s;
    }
    if (kind == CW_OP_RETRACTOR) return retractorJacobian(q, o);
    if (kind == CW_OP_PLIERS) return pliersJacobian(q, o);
    return dilatorJacobian(q, o);
}

CW_NAMESPACE_END

#endif

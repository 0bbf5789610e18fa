// The peeler (shared/operators.h has the contract it keeps).
#ifndef CUTAWAY_OPERATOR_PEELER_H
#define CUTAWAY_OPERATOR_PEELER_H

#include "shared/operator_params.h"

CW_NAMESPACE_BEGIN

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

CW_NAMESPACE_END

#endif

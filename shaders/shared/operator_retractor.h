// The retractor (shared/operators.h has the contract it keeps).
#ifndef CUTAWAY_OPERATOR_RETRACTOR_H
#define CUTAWAY_OPERATOR_RETRACTOR_H

#include "shared/operator_params.h"

CW_NAMESPACE_BEGIN

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

CW_NAMESPACE_END

#endif

// The dilator (shared/operators.h has the contract it keeps).
#ifndef CUTAWAY_OPERATOR_DILATOR_H
#define CUTAWAY_OPERATOR_DILATOR_H

#include "shared/operator_params.h"

CW_NAMESPACE_BEGIN

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

CW_NAMESPACE_END

#endif

// The pliers (shared/operators.h has the contract they keep).
#ifndef CUTAWAY_OPERATOR_PLIERS_H
#define CUTAWAY_OPERATOR_PLIERS_H

#include "shared/operator_params.h"

// max |g'(u)| of the pliers' profile g(u) = (1 - u^2)^3, at u = 1/sqrt(5):
// 96 / (25 sqrt(5)).
#define CW_PLIERS_MAX_SLOPE 1.7173002f
// Safeguarded Newton steps of the pliers' backward map (see pliersBackward).
#define CW_PLIERS_ITERATIONS 12

CW_NAMESPACE_BEGIN

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

CW_NAMESPACE_END

#endif

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
// Each operator's header (operator_peeler.h, operator_retractor.h,
// operator_pliers.h, operator_dilator.h) lists its parameter ranges, the box
// faces that stay fixed, and how its signed distance is defined; this one
// dispatches on the kind.
#ifndef CUTAWAY_OPERATORS_H
#define CUTAWAY_OPERATORS_H

#include "shared/operator_dilator.h"
#include "shared/operator_params.h"
#include "shared/operator_peeler.h"
#include "shared/operator_pliers.h"
#include "shared/operator_retractor.h"

CW_NAMESPACE_BEGIN

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

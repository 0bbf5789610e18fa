// The operators' parameters and constants (shared/operators.h has the
// contract every operator keeps), for GLSL and C++.
#ifndef CUTAWAY_OPERATOR_PARAMS_H
#define CUTAWAY_OPERATOR_PARAMS_H

#include "shared/glsl_cpp.h"

#define CW_OP_PEELER 0
#define CW_OP_RETRACTOR 1
#define CW_OP_PLIERS 2
#define CW_OP_DILATOR 3
#define CW_NO_CUT 1000.0f

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

CW_NAMESPACE_END

#endif

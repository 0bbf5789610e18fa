#version 460
// Bakes one operator into a 3D texture over its deformed box V'_T (paper
// section 5: "3D displacements"): per texel, the displacement from the texel's
// local position q to its pre-image under the continuous T_B (holes filled),
// and the signed distance to the cut (<= 0: empty).
#extension GL_GOOGLE_include_directive : require
#include "shared/operator_frame.h"
#include "shared/operators.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 4) in;
layout(set = 0, binding = CW_OPBAKE_BIND_MAP, rgba16f) uniform writeonly image3D operatorMap;
layout(push_constant) uniform Push {
    OperatorBakeParams bake;
};

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(id, bake.dims))) return;
    vec3 q = mix(bake.mapLo.xyz, bake.mapHi.xyz, (vec3(id) + 0.5) / vec3(bake.dims));
    OperatorParams o;
    o.a = bake.a;
    o.b = bake.b;
    o.kind = bake.kind;
    vec4 back = operatorBackward(q, o);
    imageStore(operatorMap, id, vec4(back.xyz - q, back.w));
}

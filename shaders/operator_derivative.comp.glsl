#version 460
// The baked map's derivatives (bake/operator_bake.hpp), for the Jacobian of
// Eq. 5 and the cut's normal of Eq. 7: per map texel t and local axis i, the
// central difference (T[t + e_i] - T[t - e_i]) / (2 texel_i) of the map's
// texels (one-sided, over one texel, at the box's faces). Section i of the
// output holds axis i: texels x + i * dims.x. Sampled trilinearly at q more
// than a texel inside the box, a section equals the central difference of
// the trilinear map over one texel around q, (map(q + texel_i e_i) -
// map(q - texel_i e_i)) / (2 texel_i), which the shaders took with six
// filtered fetches of the map: three now (mapDerivative in
// glsl/operator_sample.h).
#extension GL_GOOGLE_include_directive : require
#include "shared/operator_frame.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 4) in;
layout(set = 0, binding = 0, rgba16f) uniform readonly image3D operatorMap;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image3D derivatives;
layout(push_constant) uniform Push { OperatorBakeParams bake; };

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    ivec3 dims = bake.dims;
    if (id.x >= 3 * dims.x || id.y >= dims.y || id.z >= dims.z) return;
    int axis = id.x / dims.x;
    ivec3 t = ivec3(id.x - axis * dims.x, id.yz);
    ivec3 e = ivec3(0);
    e[axis] = 1;
    ivec3 lo = max(t - e, ivec3(0)), hi = min(t + e, dims - 1);
    float texel = (bake.mapHi[axis] - bake.mapLo[axis]) / float(dims[axis]);
    float span = float(hi[axis] - lo[axis]) * texel;
    vec4 d = span > 0.0 ? (imageLoad(operatorMap, hi) - imageLoad(operatorMap, lo)) / span
                        : vec4(0.0);
    imageStore(derivatives, id, d);
}

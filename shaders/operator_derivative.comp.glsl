#version 460
// The baked map's derivatives (bake/operator_bake.hpp), for the Jacobian of
// Eq. 5 and the cut's normal of Eq. 7, at half the map's resolution: per
// texel of the half grid and local axis i, the mean over the 2x2x2 map
// texels it covers of their central differences (T[t + e_i] - T[t - e_i]) /
// (2 texel_i) (one-sided, over one texel, at the box's faces). Section i of
// the output holds axis i: texels x + i * halfDims.x.
//
// Along an axis the trilinear map is piecewise linear between texel centres,
// so the texels' central differences, interpolated trilinearly, give the
// central difference of the trilinear map over one texel, which the shaders
// took with six filtered fetches of the map. The mean of a 2x2x2 block is
// that interpolation at the block's centre, the half texel's centre: the
// half grid is exact there and trilinear between (smoother than the map by
// a texel). Three fetches a shaded slab instead of six, in an eighth of the
// memory the full grid took (6 MB per 64^3 operator: the frog's largest
// benchmark row went past its memory goal).
#extension GL_GOOGLE_include_directive : require
#include "shared/operator_frame.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 4) in;
layout(set = 0, binding = CW_OPBAKE_BIND_MAP) uniform sampler3D operatorMap;
layout(set = 0, binding = CW_OPBAKE_BIND_DERIVATIVES,
       rgba16f) uniform writeonly image3D derivatives;
layout(push_constant) uniform Push {
    OperatorBakeParams bake;
};

// The central difference along `axis` at map texel t, per local unit.
vec4 centralDifference(ivec3 t, int axis) {
    ivec3 dims = bake.dims;
    ivec3 e = ivec3(0);
    e[axis] = 1;
    ivec3 lo = max(t - e, ivec3(0)), hi = min(t + e, dims - 1);
    float texel = (bake.mapHi[axis] - bake.mapLo[axis]) / float(dims[axis]);
    float span = float(hi[axis] - lo[axis]) * texel;
    return span > 0.0 ? (texelFetch(operatorMap, hi, 0) - texelFetch(operatorMap, lo, 0)) / span
                      : vec4(0.0);
}

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    ivec3 size = imageSize(derivatives); // bake::derivativeDims, three sections wide
    ivec3 halfDims = ivec3(size.x / 3, size.yz);
    if (id.x >= 3 * halfDims.x || id.y >= halfDims.y || id.z >= halfDims.z) return;
    int axis = id.x / halfDims.x;
    ivec3 t = ivec3(id.x - axis * halfDims.x, id.yz);
    vec4 sum = vec4(0.0);
    for (int corner = 0; corner < 8; ++corner) {
        ivec3 offset = ivec3(corner & 1, (corner >> 1) & 1, corner >> 2);
        sum += centralDifference(min(2 * t + offset, bake.dims - 1), axis);
    }
    imageStore(derivatives, id, sum / 8.0);
}

#version 460
// Distance field, passes 2 and 3 (paper section 4.2): one invocation per line
// along params.axis (y, then z), in place in the R16F field (the whole line is
// read before any of it is written). With f(q) the square of the stored
// distance, each output is the distance sqrt(min over the line of f(q) +
// (spacing * (p - q))^2), found exactly as the lower envelope of those
// parabolas (Felzenszwalb and Huttenlocher). Stored kHalfMax is infinite and
// takes no part; a line with none finite stays kHalfMax. See
// shared/feature_bake.h.
#extension GL_GOOGLE_include_directive : require
#include "shared/feature_bake.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(set = 0, binding = CW_FEATURE_BIND_SRC, r16f) uniform readonly image3D srcImage;
layout(set = 0, binding = CW_FEATURE_BIND_DST, r16f) uniform writeonly image3D dstImage;
layout(push_constant) uniform Push {
    FeatureBakeParams params;
};

int v[kEdtMaxLine];       // abscissae of the parabolas in the envelope
float fv[kEdtMaxLine];    // their values f(v[k])
float z[kEdtMaxLine + 1]; // parabola k is lowest on [z[k], z[k + 1]]

#include "glsl/line_pass.h"

void main() {
    ivec2 uv;
    int n;
    if (!invocationLine(uv, n)) return;
    float w2 = params.spacing[params.axis] * params.spacing[params.axis];

    int k = -1;
    for (int q = 0; q < n; ++q) {
        float f = squaredDistance(imageLoad(srcImage, voxel(q, uv)).r);
        if (f >= kEdtInfinite) continue;
        if (k < 0) {
            k = 0;
            v[0] = q;
            fv[0] = f;
            z[0] = -kEdtFar;
            z[1] = kEdtFar;
            continue;
        }
        float s = parabolaIntersection(f, q, fv[k], v[k], w2);
        while (s <= z[k]) { // z[0] = -kEdtFar: never pops the first parabola
            --k;
            s = parabolaIntersection(f, q, fv[k], v[k], w2);
        }
        ++k;
        v[k] = q;
        fv[k] = f;
        z[k] = s;
        z[k + 1] = kEdtFar;
    }

    if (k < 0) {
        for (int p = 0; p < n; ++p)
            imageStore(dstImage, voxel(p, uv), vec4(kHalfMax));
        return;
    }
    k = 0;
    for (int p = 0; p < n; ++p) {
        while (z[k + 1] < float(p))
            ++k;
        float d = float(p - v[k]);
        imageStore(dstImage, voxel(p, uv), vec4(storedDistance(w2 * d * d + fv[k])));
    }
}

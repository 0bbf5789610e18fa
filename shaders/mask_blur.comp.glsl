#version 460
// Segment mask (paper section 4.3): one axis of the separable Gaussian that
// smooths the segment indicator, borders clamped. One invocation per line
// along params.axis: each voxel is read once into a ring of the last
// 2 radius + 1 values, the taps are summed from there in the order of the
// CPU twin. mode 1 reads the indicator texture (the first pass), mode 0 the
// previous pass's result, in place in the R16F field. The workgroup computes
// the kernel once into shared memory. See shared/feature_bake.h.
#extension GL_GOOGLE_include_directive : require
#include "shared/feature_bake.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(set = 0, binding = 0) uniform sampler3D sourceTex;
layout(set = 0, binding = 1, r16f) uniform readonly image3D srcImage;
layout(set = 0, binding = 2, r16f) uniform writeonly image3D dstImage;
layout(push_constant) uniform Push { FeatureBakeParams params; };

const int kRing = 128; // a power of two > 2 kBlurMaxRadius + 1
shared float weights[kBlurMaxRadius + 1];
float ring[kRing];

#include "glsl/line_pass.h"

float at(int i, ivec2 uv) {
    ivec3 p = voxel(clamp(i, 0, params.dims[params.axis] - 1), uv);
    return params.mode == 1 ? texelFetch(sourceTex, p, 0).r : imageLoad(srcImage, p).r;
}

void main() {
    for (uint i = gl_LocalInvocationIndex; i <= uint(kBlurMaxRadius); i += 64u)
        weights[i] = gaussianWeight(int(i), params.sigma);
    barrier();

    ivec2 uv;
    int n;
    if (!invocationLine(uv, n)) return;
    int r = params.radius;
    float weightSum = 0.0;
    for (int i = -r; i <= r; ++i) weightSum += weights[abs(i)];
    // ring[(q + r) % kRing] holds the value at q, for q in [p - r, p + r].
    for (int q = -r; q < r; ++q) ring[(q + r) & (kRing - 1)] = at(q, uv);
    for (int p = 0; p < n; ++p) {
        ring[(p + 2 * r) & (kRing - 1)] = at(p + r, uv);
        float sum = 0.0;
        for (int i = -r; i <= r; ++i) sum += weights[abs(i)] * ring[(p + i + r) & (kRing - 1)];
        imageStore(dstImage, voxel(p, uv), vec4(sum / weightSum));
    }
}

#version 460
// Segment mask (paper section 4.3): one axis of the separable Gaussian that
// smooths the segment indicator, borders clamped. One invocation per line
// along params.axis: each voxel is read once, ahead of the voxel being
// written, into a sliding window of 2 kWindow + 1 values, and the taps are
// summed from there in the order of the CPU twin. mode 1 reads the indicator
// texture (the first pass), mode 0 the previous pass's result, in place in
// the R16F field. The workgroup computes the kernel once into shared memory.
// See shared/feature_bake.h.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "shared/feature_bake.h"

// The largest radius this pipeline takes (<= kBlurMaxRadius). The loops over
// the window are unrolled, so every index into it is a constant and the
// window lives in registers; a window indexed at run time (a ring) is kept
// in memory lane by lane on lavapipe, 3-6x slower. Taps beyond params.radius
// weigh 0 and add exactly nothing: the sum is the CPU twin's, term by term.
layout(constant_id = CW_FEATURE_SPEC_BLUR_WINDOW) const int kWindow = kBlurMaxRadius;

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(set = 0, binding = CW_FEATURE_BIND_SOURCE) uniform sampler3D sourceTex;
layout(set = 0, binding = CW_FEATURE_BIND_SRC, r16f) uniform readonly image3D srcImage;
layout(set = 0, binding = CW_FEATURE_BIND_DST, r16f) uniform writeonly image3D dstImage;
layout(push_constant) uniform Push {
    FeatureBakeParams params;
};

shared float weights[kBlurMaxRadius + 1];

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
    for (int i = -r; i <= r; ++i)
        weightSum += weights[abs(i)];
    float w[kWindow + 1];
    [[unroll]] for (int i = 0; i <= kWindow; ++i) w[i] = i <= r ? weights[i] : 0.0;
    // window[j] holds the value at p - kWindow + j.
    float window[2 * kWindow + 1];
    [[unroll]] for (int j = 0; j < 2 * kWindow; ++j) window[j + 1] = at(j - kWindow, uv);
    for (int p = 0; p < n; ++p) {
        [[unroll]] for (int j = 0; j < 2 * kWindow; ++j) window[j] = window[j + 1];
        window[2 * kWindow] = at(p + kWindow, uv);
        float sum = 0.0;
        [[unroll]] for (int j = 0; j <= 2 * kWindow; ++j) sum += w[abs(j - kWindow)] * window[j];
        imageStore(dstImage, voxel(p, uv), vec4(sum / weightSum));
    }
}

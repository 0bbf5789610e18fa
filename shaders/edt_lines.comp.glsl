#version 460
// Distance field, pass 1 (paper section 4.2): one invocation per x line.
// Thresholds the volume texture (object: value > threshold) and writes the
// distance in mm along x to the nearest background voxel, kHalfMax where the
// line has none, into the R16F field itself. Two sweeps: the forward one
// leaves the voxel count since the last background voxel in the image (at
// most kHalfMax: counts up to 2048 are exact in half precision), the backward
// one takes the minimum with the count to the next. See shared/feature_bake.h.
#extension GL_GOOGLE_include_directive : require
#include "shared/feature_bake.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(set = 0, binding = CW_FEATURE_BIND_SOURCE) uniform sampler3D sourceTex;
layout(set = 0, binding = CW_FEATURE_BIND_DST, r16f) uniform image3D dstImage;
layout(push_constant) uniform Push {
    FeatureBakeParams params;
};

void main() {
    ivec2 yz = ivec2(gl_GlobalInvocationID.xy);
    if (yz.x >= params.dims.y || yz.y >= params.dims.z) return;
    int n = params.dims.x;
    float run = kEdtFar; // kEdtFar + 1 == kEdtFar: stays "none yet"
    for (int x = 0; x < n; ++x) {
        bool object = texelFetch(sourceTex, ivec3(x, yz), 0).r > params.threshold;
        run = object ? run + 1.0 : 0.0;
        imageStore(dstImage, ivec3(x, yz), vec4(min(run, kHalfMax)));
    }
    run = kEdtFar;
    for (int x = n - 1; x >= 0; --x) {
        float left = imageLoad(dstImage, ivec3(x, yz)).r;
        run = left == 0.0 ? 0.0 : run + 1.0;
        float d = min(left >= kHalfMax ? kEdtFar : left, run);
        float mm = d >= kEdtInfinite ? kHalfMax : min(d * params.spacing.x, kHalfMax);
        imageStore(dstImage, ivec3(x, yz), vec4(mm));
    }
}

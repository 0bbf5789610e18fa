#version 460
// Bakes the gradient of the normalized volume once per volume (section 5 of
// the paper: "the gradients can also be stored as textures"). A 3x3x3
// operator, Farid and Simoncelli's matched pair; see shared/gradient.h.
// flavours: storage
#extension GL_GOOGLE_include_directive : require
#include "shared/gradient.h"

// Each invocation bakes a block kRun voxels wide along x and kColumn deep
// along z, walking z with a sliding window of three planes. The operator is
// separable (gradientWeight: the prefilter across each axis it does not
// differentiate), so each plane keeps, per column x, the value smoothed
// along y and its difference along y: (kRun + 2) * 3 texel fetches per plane
// for kRun voxels (4.5 per voxel instead of 9) and a few adds per voxel
// instead of 27 weighted terms per axis.
#define kColumn 16
#define kRun 4
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(set = 0, binding = CW_GRADIENT_BIND_VALUES) uniform sampler3D volumeTex;
layout(set = 0, binding = CW_GRADIENT_BIND_OUT,
       rgba8_snorm) uniform writeonly image3D gradientImage;
#ifdef CW_STORAGE_PATHS
// The values read as the storage image they also are (bake::ValueStorageBindings):
// 0: sampled; 1: the R8 image volumeImage8; 2: the R16 one, volumeImage16.
// On lavapipe a texel fetch of a sampled 8- or 16-bit image is a call,
// imageLoad an inline load (as for the renderers, sample_common.h).
layout(constant_id = CW_GRADIENT_SPEC_STORAGE_FETCH) const int cwStorageFetch = 0;
layout(set = 0, binding = CW_GRADIENT_BIND_VALUES_R8, r8) uniform readonly image3D volumeImage8;
layout(set = 0, binding = CW_GRADIENT_BIND_VALUES_R16, r16) uniform readonly image3D volumeImage16;
#endif
layout(push_constant) uniform Push {
    GradientParams params;
};

float at(ivec3 p) {
    ivec3 q = clamp(p, ivec3(0), params.dims - 1);
#ifdef CW_STORAGE_PATHS
    if (cwStorageFetch == 1) return imageLoad(volumeImage8, q).r;
    if (cwStorageFetch == 2) return imageLoad(volumeImage16, q).r;
#endif
    return texelFetch(volumeTex, q, 0).r;
}

// Plane k of the window (0: z - 1, 1: z, 2: z + 1), column i (x - 1 + i):
// the value prefiltered along y and its central difference along y.
float smoothY[3][kRun + 2];
float diffY[3][kRun + 2];

// The prefilter over three neighbours along one axis. It adds a voxel's two
// neighbours first, so a volume mirrored about a plane bakes the mirrored
// gradient to the bit (rounding does not depend on the side).
float prefilter(float below, float here, float above) {
    return (below + above) * kGradientSideTap + here * kGradientMiddleTap;
}

void loadPlane(int k, ivec3 p) {
    for (int i = 0; i < kRun + 2; ++i) {
        ivec3 q = p + ivec3(i - 1, 0, 0);
        float below = at(q - ivec3(0, 1, 0)), here = at(q), above = at(q + ivec3(0, 1, 0));
        smoothY[k][i] = prefilter(below, here, above);
        diffY[k][i] = above - below;
    }
}

// The prefilter across x of `row` around column i.
float smoothX(float row[kRun + 2], int i) {
    return prefilter(row[i - 1], row[i], row[i + 1]);
}

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID.x * kRun, gl_GlobalInvocationID.y,
                     gl_GlobalInvocationID.z * kColumn);
    if (id.x >= params.dims.x || id.y >= params.dims.y || id.z >= params.dims.z) return;
    loadPlane(0, id + ivec3(0, 0, -1));
    loadPlane(1, id);
    for (int s = 0; s < kColumn && id.z + s < params.dims.z; ++s) {
        loadPlane(2, id + ivec3(0, 0, s + 1));
        for (int r = 0; r < kRun; ++r) {
            if (id.x + r >= params.dims.x) break;
            int i = r + 1;
            vec3 delta;
            delta.x = prefilter(smoothY[0][i + 1] - smoothY[0][i - 1],
                              smoothY[1][i + 1] - smoothY[1][i - 1],
                              smoothY[2][i + 1] - smoothY[2][i - 1]);
            delta.y = prefilter(smoothX(diffY[0], i), smoothX(diffY[1], i), smoothX(diffY[2], i));
            delta.z = smoothX(smoothY[2], i) - smoothX(smoothY[0], i);
            ivec3 voxel = id + ivec3(r, 0, s);
            imageStore(gradientImage, params.bricked != 0 ? gradientBrickTexel(voxel) : voxel,
                       encodeGradient(delta, params));
        }
        smoothY[0] = smoothY[1];
        smoothY[1] = smoothY[2];
        diffY[0] = diffY[1];
        diffY[1] = diffY[2];
    }
}

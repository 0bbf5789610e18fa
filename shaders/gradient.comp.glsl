#version 460
// Bakes the gradient of the normalized volume once per volume (section 5 of
// the paper: "the gradients can also be stored as textures"). 3x3x3 Sobel-style
// operator; see shared/gradient.h.
#extension GL_GOOGLE_include_directive : require
#include "shared/gradient.h"

// Each invocation walks a column of kColumn voxels along z with a sliding
// window of three 3x3 planes: 9 texel fetches per voxel instead of the
// operator's 54 (what a software rasterizer pays for, fetch by fetch).
#define kColumn 16
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(set = 0, binding = 0) uniform sampler3D volumeTex;
layout(set = 0, binding = 1, rgba8_snorm) uniform writeonly image3D gradientImage;
layout(push_constant) uniform Push { GradientParams params; };

float at(ivec3 p) { return texelFetch(volumeTex, clamp(p, ivec3(0), params.dims - 1), 0).r; }

// planes[k][(x + 1) + 3 * (y + 1)]: plane k of the window (0: z - 1, 1: z, 2: z + 1).
float planes[3][9];

void loadPlane(int k, ivec3 p) {
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x)
            planes[k][(x + 1) + 3 * (y + 1)] = at(p + ivec3(x, y, 0));
}

float v(int x, int y, int z) { return planes[z + 1][(x + 1) + 3 * (y + 1)]; }

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID.xy, gl_GlobalInvocationID.z * kColumn);
    if (id.x >= params.dims.x || id.y >= params.dims.y || id.z >= params.dims.z) return;
    loadPlane(0, id + ivec3(0, 0, -1));
    loadPlane(1, id);
    for (int i = 0; i < kColumn && id.z + i < params.dims.z; ++i) {
        ivec3 p = id + ivec3(0, 0, i);
        loadPlane(2, p + ivec3(0, 0, 1));
        vec3 delta = vec3(0.0);
        for (int a = -1; a <= 1; ++a) {
            for (int b = -1; b <= 1; ++b) {
                float w = sobelWeight(a, b);
                delta.x += w * (v(1, a, b) - v(-1, a, b));
                delta.y += w * (v(a, 1, b) - v(a, -1, b));
                delta.z += w * (v(a, b, 1) - v(a, b, -1));
            }
        }
        imageStore(gradientImage, p, encodeGradient(delta, params));
        planes[0] = planes[1];
        planes[1] = planes[2];
    }
}

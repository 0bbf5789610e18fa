#version 460
// Bakes the gradient of the normalized volume once per volume (section 5 of
// the paper: "the gradients can also be stored as textures"). 3x3x3 Sobel-style
// operator; see shared/gradient.h.
#extension GL_GOOGLE_include_directive : require
#include "shared/gradient.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 4) in;
layout(set = 0, binding = 0) uniform sampler3D volumeTex;
layout(set = 0, binding = 1, rgba8_snorm) uniform writeonly image3D gradientImage;
layout(push_constant) uniform Push { GradientParams params; };

float at(ivec3 p) { return texelFetch(volumeTex, clamp(p, ivec3(0), params.dims - 1), 0).r; }

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(id, params.dims))) return;
    vec3 delta = vec3(0.0);
    for (int a = -1; a <= 1; ++a) {
        for (int b = -1; b <= 1; ++b) {
            float w = sobelWeight(a, b);
            delta.x += w * (at(id + ivec3(1, a, b)) - at(id + ivec3(-1, a, b)));
            delta.y += w * (at(id + ivec3(a, 1, b)) - at(id + ivec3(a, -1, b)));
            delta.z += w * (at(id + ivec3(a, b, 1)) - at(id + ivec3(a, b, -1)));
        }
    }
    imageStore(gradientImage, id, encodeGradient(delta, params));
}

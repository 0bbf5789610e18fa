#version 460
// Ray casting (render.method "raycast", docs/performance.md): one invocation
// per pixel marches its ray front to back, taking its samples where the ray
// crosses the slicing planes s_k = (k + 0.5) * spacing, so it samples exactly
// where slicing would and calls the same per-sample code (sample_common.h).
// What it saves over slicing: a slab's back value is the next slab's front
// (one volume fetch per sample instead of two), no rasterization or blending,
// and a ray stops the moment it is opaque. It also steps over empty cells,
// and takes the gradient and lighting only at visible slabs: lavapipe runs 8
// rays in lock-step and pays for both sides of a branch, but a loop ends when
// all its lanes leave it, so transparent runs are an inner loop of their own.
// Scenes without operators only.
#extension GL_GOOGLE_include_directive : require
#include "glsl/sample_common.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(set = 0, binding = 5, rgba32f) uniform writeonly image2D target;
// One texel per cell of kRayCellVoxels^3 (render/ray_cells.hpp): 0 where the
// cell is occupied; else r, and every cell within r - 1 of it (chessboard
// distance) is empty: each sample there, and each slab up to the margin long
// that starts there, is transparent.
layout(set = 0, binding = 6) uniform usampler3D cellTex;
// transferTex's alpha alone (the same half values, R16F): transparent runs
// look up only that; the whole texel is read once a slab shows.
layout(set = 0, binding = 7) uniform sampler2DArray alphaTex;
layout(push_constant) uniform Ray {
    mat4 clipToWorld;
    vec4 boxLo; // the occupied cells' bounds (world, mm)
    vec4 boxHi;
    vec4 cellsPerTexture; // xyz: cells across the texture, the last one partial;
                          // w: the longest slab they cover (voxels along each axis)
} ray;

// How many steps of `tcStep` from `tc` until the ray leaves the cube of empty
// cells around the cell it is in, when that cell is empty and the ray's slabs
// are no longer than the cells' margin; 0 otherwise. Never steps past a sample
// outside the cube, so it skips only samples (and the slabs they start) that
// the cells say are transparent.
float stepsOverEmpty(vec3 tc, vec3 tcStep, bool slabsInMargin) {
    vec3 at = tc * ray.cellsPerTexture.xyz;
    ivec3 cell = clamp(ivec3(floor(at)), ivec3(0), textureSize(cellTex, 0) - 1);
    uint free = texelFetch(cellTex, cell, 0).r;
    if (!slabsInMargin || free == 0u) return 0.0;
    vec3 step = tcStep * ray.cellsPerTexture.xyz;
    float r = float(free); // the empty cube: cells [cell - (r - 1), cell + r)
    vec3 wall = vec3(cell) + mix(vec3(1.0 - r), vec3(r), greaterThan(step, vec3(0.0)));
    vec3 toWall = mix(vec3(1e30), (wall - at) / step, greaterThan(abs(step), vec3(1e-12)));
    return max(1.0, ceil(min(toWall.x, min(toWall.y, toWall.z))));
}

// The table's alpha for the slab from `front` to `back`: classifySlab's
// lookup before the opacity correction, the same half values filtered alike,
// so 0 exactly where the table gives classifySlab no opacity.
float slabAlpha(float front, float back, float layer) {
    vec2 at = cwPreintegrated ? vec2(front, back) * u.valueToTf.x + u.valueToTf.y
                              : vec2(front * u.valueToTf.x + u.valueToTf.y, 0.5);
    return textureLod(alphaTex, vec3(at, layer), 0.0).r;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(target);
    if (pixel.x >= size.x || pixel.y >= size.y) return;
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(size) * 2.0 - 1.0;
    vec4 nearH = ray.clipToWorld * vec4(ndc, 0.0, 1.0);
    vec4 farH = ray.clipToWorld * vec4(ndc, 1.0, 1.0);
    vec3 origin = nearH.xyz / nearH.w; // on the near plane: nothing in front of it is drawn
    vec3 dir = normalize(farH.xyz / farH.w - origin);

    vec3 inv = 1.0 / dir;
    vec3 ta = (ray.boxLo.xyz - origin) * inv, tb = (ray.boxHi.xyz - origin) * inv;
    vec3 tMin = min(ta, tb), tMax = max(ta, tb);
    float tEnter = max(max(tMin.x, tMin.y), max(tMin.z, 0.0));
    float tExit = min(min(tMax.x, tMax.y), tMax.z);
    vec4 sum = vec4(0.0);
    if (tEnter < tExit) {
        vec3 f = u.viewDir.xyz;
        float spacing = u.viewDir.w;
        float fd = dot(f, dir), so = dot(f, origin);
        float first = ceil((so + tEnter * fd) / spacing - 0.5);
        float last = floor((so + tExit * fd) / spacing - 0.5);
        vec3 toEye = -dir;
        float obliquity = obliquityOf(toEye);
        vec3 step = dir * (spacing * obliquity); // from one plane to the next along the ray
        vec3 p = origin + dir * (((first + 0.5) * spacing - so) / fd);
        vec3 tc = toTexture(p);
        vec3 tcStep = toTexture(p + step) - tc;
        // The cells cover slabs up to cellsPerTexture.w voxels long.
        vec3 voxelStep = abs(tcStep) * vec3(textureSize(volumeTex, 0));
        bool slabsInMargin = max(voxelStep.x, max(voxelStep.y, voxelStep.z)) <= ray.cellsPerTexture.w;
        float front = textureLod(volumeTex, tc, 0.0).r;
        float k = first;
        bool haveFront = true; // false after stepping over empty cells
        while (k <= last) {
            // Transparent slabs cost a volume fetch and a lookup of the
            // table's alpha, empty cells a cell lookup; the whole table texel,
            // the gradient and the lighting run once every lane is at a
            // visible slab or done.
            float next = 0.0;
            vec4 c = vec4(0.0);
            while (k <= last) {
                float skip = stepsOverEmpty(tc, tcStep, slabsInMargin);
                if (skip > 0.0) {
                    k += skip;
                    tc += skip * tcStep;
                    haveFront = false;
                    continue;
                }
                float value = textureLod(volumeTex, haveFront ? tc + tcStep : tc, 0.0).r;
                if (!haveFront) {
                    front = value;
                    haveFront = true;
                    continue;
                }
                next = value;
                if (slabAlpha(front, cwPreintegrated ? next : front, classLayer(tc)) > 0.0) break;
                tc += tcStep;
                front = next;
                k += 1.0;
            }
            if (k > last) break;
            c = classifySlab(front, cwPreintegrated ? next : front, obliquity, classLayer(tc));
            vec3 shadeAt = cwPreintegrated ? tc + 0.5 * tcStep : tc;
            c = shade(c, textureLod(gradientTex, shadeAt, 0.0), toEye);
            sum += (1.0 - sum.a) * c;
            if (sum.a >= CW_OPAQUE_ALPHA) break;
            tc += tcStep;
            front = next;
            k += 1.0;
        }
    }
    imageStore(target, pixel, sum);
}

// GLSL only: the resources and per-sample steps that the slicing fragment
// shaders and the ray-casting compute shader share. (Math that the C++ tests
// also run lives in shaders/shared/.)
#ifndef CUTAWAY_SAMPLE_COMMON_H
#define CUTAWAY_SAMPLE_COMMON_H

#include "shared/bindings.h"

// What a frame fixes, as specialization constants (ShaderVariant in
// render/shader_variant.hpp): the compiler drops the paths a frame does
// not take. On lavapipe a branch on a uniform still costs both sides, so these halve the cost of a
// fragment.
layout(constant_id = CW_SPEC_PREINTEGRATED) const bool cwPreintegrated = false;
layout(constant_id = CW_SPEC_BY_LABEL) const bool cwByLabel = false;
layout(constant_id = CW_SPEC_SHADING) const bool cwShading = true;
layout(constant_id = CW_SPEC_LIGHT_COUNT) const int cwLightCount = 0;
layout(constant_id = CW_SPEC_ALIGNMENT) const int cwAlignment = 0; // operator proxies: CW_ALIGN_*
#ifdef CW_STORAGE_PATHS
// The CPU-device paths (gpu/device_tuning.hpp); shaders built without
// CW_STORAGE_PATHS declare none of their bindings.
// The volume's values read as a storage image and filtered here (volumeAt)
// instead of sampled: on lavapipe a sampled fetch of an 8- or 16-bit texture
// is a call that gathers its 64 texels one by one, imageLoad an inline load
// (docs/design/cpu-device-paths.md). 0: sampled; 1: the R8 storage image
// volumeImage8; 2: the R16 one, volumeImage16.
layout(constant_id = CW_SPEC_STORAGE_FETCH) const int cwStorageFetch = 0;
// The gradients in the bricked layout (bake::GradientLayout::Bricked), read
// as the storage image gradientImage and filtered here (gradientAt); else
// sampled from gradientTex.
layout(constant_id = CW_SPEC_BRICKED_GRADIENTS) const bool cwBrickedGradients = false;
#else
const int cwStorageFetch = 0;
const bool cwBrickedGradients = false;
#endif
// /render/filter: false linear (the sampler's trilinear filter), true the
// tricubic Catmull-Rom filter (shared/cubic_filter.h) for the values and the
// gradients.
layout(constant_id = CW_SPEC_CUBIC) const bool cwCubic = false;
// /render/refine: the sub-slabs a pre-integrated slab that shows is taken in
// (backgroundSlab, refinedOperatorSlab); 1 none.
layout(constant_id = CW_SPEC_REFINE) const int cwRefine = 1;
// The shininess when it is a whole number (scene range: up to 512), else 0.
layout(constant_id = CW_SPEC_WHOLE_SHININESS) const int cwWholeShininess = 0;
// The label channels (/output/aovs "label", /output/mattes): classTex
// carries each voxel's label and matte (classTexel).
layout(constant_id = CW_SPEC_LABEL_AOVS) const bool cwLabelAovs = false;
layout(constant_id = CW_SPEC_MATTES) const bool cwMattes = false;
#define CW_SHADING_ON(u) cwShading
#define CW_LIGHT_COUNT(u) cwLightCount

// x^n for the specular highlight: with a whole-number shininess, by repeated
// squaring over the bits of the constant, which the compiler unrolls into
// the few products n needs (5 for the default 32) instead of pow's log2 and
// exp2 (about 5 % of a ct_head frame without an operator on lavapipe).
float specularPower(float x, float n) {
    if (cwWholeShininess <= 0) return pow(x, n);
    float result = 1.0, square = x;
    for (int bit = 0; bit < 10; ++bit) { // 512 < 2^10
        if ((cwWholeShininess & (1 << bit)) != 0) result *= square;
        square *= square;
    }
    return result;
}
#define CW_SPECULAR_POWER(x, n) specularPower(x, n)

#include "shared/cubic_filter.h"
#include "shared/frame.h"
#include "shared/gradient.h"
#include "shared/sampling.h"
#include "shared/shading.h"

layout(std140, set = 0, binding = CW_BIND_FRAME) uniform Frame {
    FrameUniforms u;
};
layout(set = 0, binding = CW_BIND_VALUES) uniform sampler3D volumeTex;
layout(set = 0, binding = CW_BIND_GRADIENTS) uniform sampler3D gradientTex;
// One classification table per layer: layer 0 is /transfer, layer i + 1
// /transfer/labels/i. classTex holds each voxel's layer (classification by
// label; a 1^3 texture of 0 without labels, and u.flags.w = 0).
layout(set = 0, binding = CW_BIND_TRANSFER) uniform sampler2DArray transferTex;
layout(set = 0, binding = CW_BIND_CLASSES) uniform usampler3D classTex;
#ifdef CW_STORAGE_PATHS
// The value texture again, as a storage image of its format (see
// cwStorageFetch); a 1^3 stand-in in the binding of the other format.
layout(set = 0, binding = CW_BIND_VALUES_R8, r8) uniform readonly image3D volumeImage8;
layout(set = 0, binding = CW_BIND_VALUES_R16, r16) uniform readonly image3D volumeImage16;
// The gradients again, as a storage image (see cwBrickedGradients).
layout(set = 0, binding = CW_BIND_GRADIENT_IMAGE,
       rgba8_snorm) uniform readonly image3D gradientImage;
#endif

// The operator-id codes of the proxy a pixel's first visible sample came
// from: 0 nothing visible, 2 the untouched volume, 3 + i operator i. A
// sample is visible when its opacity reaches CW_ID_MIN_ALPHA.
#define CW_ID_BACKGROUND 2.0
#define CW_ID_MIN_ALPHA 0.01

vec3 toTexture(vec3 world) {
    return (u.worldToTexture * vec4(world, 1.0)).xyz;
}

// The value texel at voxel p of the storage image cwStorageFetch names (the
// constant folds the choice away).
float valueTexel(ivec3 p) {
#ifdef CW_STORAGE_PATHS
    return cwStorageFetch == 1 ? imageLoad(volumeImage8, p).r : imageLoad(volumeImage16, p).r;
#else
    return 0.0; // never called: cwStorageFetch is 0
#endif
}

// The size of the storage image cwStorageFetch names.
ivec3 valueImageSize() {
#ifdef CW_STORAGE_PATHS
    return cwStorageFetch == 1 ? imageSize(volumeImage8) : imageSize(volumeImage16);
#else
    return ivec3(1);
#endif
}

// The texels a trilinear, clamped-to-edge sample at texture coordinate tc of
// a grid of `dims` weighs (lo and hi corners), and its weights toward hi.
struct Trilinear {
    ivec3 lo, hi;
    vec3 f;
};

Trilinear trilinearAt(vec3 tc, ivec3 dims) {
    Trilinear t;
    vec3 pos = clamp(tc * vec3(dims) - 0.5, vec3(0.0), vec3(dims - 1));
    t.lo = ivec3(pos); // pos >= 0: truncation is floor
    t.hi = min(t.lo + 1, dims - 1);
    t.f = pos - vec3(t.lo);
    return t;
}

// The trilinear sum of a cell's eight texels with weights `f` toward its hi
// corner (Trilinear.f): `near` the four at lo.z, `far` those at hi.z, each x
// fastest (lo.x lo.y, hi.x lo.y, lo.x hi.y, hi.x hi.y).
float weighTexels(vec3 f, vec4 near, vec4 far) {
    vec4 z = mix(near, far, f.z);
    vec2 y = mix(z.xy, z.zw, f.y);
    return mix(y.x, y.y, f.x);
}

// The volume's normalized value at texture coordinate tc: trilinear, clamped
// to the edge, as textureLod(volumeTex, tc, 0.0).r samples it. With
// cwStorageFetch the eight texels are loaded and weighted here, in full float
// precision (lavapipe filters 8-bit textures with 8-bit weights).
float volumeLinearAt(vec3 tc) {
    if (cwStorageFetch == 0) return textureLod(volumeTex, tc, 0.0).r;
    Trilinear t = trilinearAt(tc, valueImageSize());
    ivec3 lo = t.lo, hi = t.hi;
    vec4 near = vec4(valueTexel(lo), valueTexel(ivec3(hi.x, lo.yz)),
                     valueTexel(ivec3(lo.x, hi.y, lo.z)), valueTexel(ivec3(hi.xy, lo.z)));
    vec4 far = vec4(valueTexel(ivec3(lo.xy, hi.z)), valueTexel(ivec3(hi.x, lo.y, hi.z)),
                    valueTexel(ivec3(lo.x, hi.yz)), valueTexel(hi));
    return weighTexels(t.f, near, far);
}

vec4 gradientTexel(ivec3 voxel) {
#ifdef CW_STORAGE_PATHS
    return imageLoad(gradientImage, gradientBrickTexel(voxel));
#else
    return vec4(0.0); // never called: cwBrickedGradients is false
#endif
}

// The baked gradient at texture coordinate tc (shared/gradient.h), filtered
// as volumeAt filters the values. Bricked, its eight texels are loaded and
// weighted here: on lavapipe a sampled fetch is a call that gathers them
// from the grid's rows and slices, about 4 cache lines a sample, where the
// bricked texels share about 3, and the next samples' mostly the same
// (docs/design/cpu-device-paths.md).
vec4 gradientLinearAt(vec3 tc) {
    if (!cwBrickedGradients) return textureLod(gradientTex, tc, 0.0);
    Trilinear t = trilinearAt(tc, textureSize(volumeTex, 0)); // the grid, not the bricks
    ivec3 lo = t.lo, hi = t.hi;
    vec4 x00 = mix(gradientTexel(lo), gradientTexel(ivec3(hi.x, lo.yz)), t.f.x);
    vec4 x10 =
        mix(gradientTexel(ivec3(lo.x, hi.y, lo.z)), gradientTexel(ivec3(hi.xy, lo.z)), t.f.x);
    vec4 x01 =
        mix(gradientTexel(ivec3(lo.xy, hi.z)), gradientTexel(ivec3(hi.x, lo.y, hi.z)), t.f.x);
    vec4 x11 = mix(gradientTexel(ivec3(lo.x, hi.yz)), gradientTexel(hi), t.f.x);
    return mix(mix(x00, x10, t.f.y), mix(x01, x11, t.f.y), t.f.z);
}

// The value texel at voxel p, loaded from the storage image or fetched
// from volumeTex, as cwStorageFetch says.
float valueVoxel(ivec3 p) {
    return cwStorageFetch == 0 ? texelFetch(volumeTex, p, 0).r : valueTexel(p);
}

// The gradient texel of voxel p, loaded from the bricks or fetched from
// gradientTex, as cwBrickedGradients says.
vec4 gradientVoxel(ivec3 p) {
    return cwBrickedGradients ? gradientTexel(p) : texelFetch(gradientTex, p, 0);
}

// The volume's value at tc as /render/filter reconstructs it: volumeLinearAt,
// or Catmull-Rom over the 4^3 texels around tc (shared/cubic_filter.h), held
// to the range of the eight of its cell.
float volumeAt(vec3 tc) {
    if (!cwCubic) return volumeLinearAt(tc);
    CubicCell c = cubicCell(tc, textureSize(volumeTex, 0));
    float sum = 0.0, lo = 1.0, hi = 0.0;
    for (int z = 0; z < 4; ++z)
        for (int y = 0; y < 4; ++y) {
            float row = 0.0;
            for (int x = 0; x < 4; ++x) {
                float v = valueVoxel(ivec3(c.ix[x], c.iy[y], c.iz[z]));
                row += c.wx[x] * v;
                if (inCubicCell(x, y, z)) {
                    lo = min(lo, v);
                    hi = max(hi, v);
                }
            }
            sum += c.wz[z] * c.wy[y] * row;
        }
    return clamp(sum, lo, hi);
}

// The gradient at tc as /render/filter reconstructs it, as volumeAt does
// the values (not held to a range: a direction and a magnitude).
vec4 gradientAt(vec3 tc) {
    if (!cwCubic) return gradientLinearAt(tc);
    CubicCell c = cubicCell(tc, textureSize(volumeTex, 0)); // the grid, not the bricks
    vec4 sum = vec4(0.0);
    for (int z = 0; z < 4; ++z)
        for (int y = 0; y < 4; ++y) {
            vec4 row = vec4(0.0);
            for (int x = 0; x < 4; ++x)
                row += c.wx[x] * gradientVoxel(ivec3(c.ix[x], c.iy[y], c.iz[z]));
            sum += (c.wz[z] * c.wy[y]) * row;
        }
    return sum;
}

vec3 toEyeFrom(vec3 world) {
    return u.eye.w > 0.5 ? normalize(u.eye.xyz - world) : -u.viewDir.xyz;
}

// 1 / cos of the angle between this pixel's ray and the view direction: planes
// are u.viewDir.w apart along the view, an oblique ray crosses more material.
float obliquityOf(vec3 toEye) {
    return 1.0 / max(dot(-toEye, u.viewDir.xyz), 1e-3);
}

// classTex's texel of the voxel nearest to texture coordinate tc: its
// classification layer in bits 0-7 and, with the label channels
// (cwLabelAovs, cwMattes), its matte (1..6, 0 none) in bits 8-11 and its
// label's code (the id less the lowest id, plus 1) in bits 12-31
// (render/classify/label_classes.hpp, labelChannelTexels).
uint classTexel(vec3 tc) {
    ivec3 dims = textureSize(classTex, 0);
    ivec3 voxel = clamp(ivec3(floor(tc * vec3(dims))), ivec3(0), dims - 1);
    return texelFetch(classTex, voxel, 0).r;
}

// The classification layer of the voxel nearest to texture coordinate tc.
float classLayer(vec3 tc) {
    if (!cwByLabel) return 0.0;
    return float(classTexel(tc) & 0xffu);
}

// The "Z" channel's depth of the slab whose front lies at `at` (both methods
// sample on the slicing planes, u.viewDir.w apart along the view): a
// pre-integrated slab's middle, since its opacity lies between its planes;
// a point sample's own plane.
float slabDepth(vec3 at) {
    return viewDepth(u, at) + (cwPreintegrated ? 0.5 * u.viewDir.w : 0.0);
}

// The label code of the voxel nearest to tc (see classTexel); 0 without
// the label channel.
float labelCode(vec3 tc) {
    return cwLabelAovs ? float(classTexel(tc) >> 12) : 0.0;
}

// Opacity `alpha` of a sample at tc in the mattes' channels: slots 1..3 in
// `first`, 4..6 in `second` (see classTexel).
void matteShares(vec3 tc, float alpha, out vec3 first, out vec3 second) {
    int slot = int((classTexel(tc) >> 8) & 0xfu);
    first = alpha * vec3(equal(ivec3(slot), ivec3(1, 2, 3)));
    second = alpha * vec3(equal(ivec3(slot), ivec3(4, 5, 6)));
}

// Premultiplied colour of the slab from `front` to `back` (normalized values),
// classified by table `layer`.
vec4 classifySlab(float front, float back, float obliquity, float layer) {
    if (cwPreintegrated) {
        vec2 at = vec2(front, back) * u.valueToTf.x + u.valueToTf.y;
        vec4 slab = textureLod(transferTex, vec3(at, layer), 0.0);
        if (slab.a <= 0.0) return vec4(0.0);
        float alpha = correctOpacity(slab.a, obliquity); // the table is for an axial slab
        return vec4(slab.rgb * (alpha / slab.a), alpha);
    }
    vec4 c = textureLod(transferTex, vec3(front * u.valueToTf.x + u.valueToTf.y, 0.5, layer), 0.0);
    if (c.a <= 0.0) return vec4(0.0);
    float alpha = correctOpacity(c.a, u.viewDir.w * obliquity / u.valueToTf.z);
    return vec4(c.rgb * alpha, alpha);
}

vec4 shade(vec4 sampleColor, vec4 gradient, Viewer viewer) {
    Lighting light = lightSample(gradient, viewer, u);
    return vec4(sampleColor.rgb * light.diffuse + light.specular * sampleColor.a, sampleColor.a);
}

// Whether a pre-integrated slab that shows is taken in cwRefine sub-slabs.
// Each slab's own approximations (the value taken as linear across it, the
// light taken at one point of it, a cut or a face clipped linearly) are most
// of what keeps a picture of one slab per voxel from converging; sub-slabs
// only where something shows cost a fraction of finer slicing
// (docs/quality.md).
bool refines() {
    return cwPreintegrated && cwRefine > 1;
}

// The untouched volume's premultiplied, shaded colour for the slab from
// texture coordinate `tc` (value `front`) to tc + tcStep (value `back`; the
// same when post-classified), seen from `viewer`, given its classification
// `coarse` = classifySlab(front, back, obliquity, classLayer(tc)) when that
// shows (a > 0; callers skip the rest). A pre-integrated slab (refines) is
// taken in cwRefine sub-slabs, each classified between values fetched at its
// ends, lit at its middle and composited front to back; else it is lit
// once, at its middle (post-classified: at its sample). Slicing and ray
// casting both call this.
vec4 backgroundSlab(vec4 coarse, float front, float back, vec3 tc, vec3 tcStep, Viewer viewer,
                    float obliquity) {
    if (!refines())
        return shade(coarse, gradientAt(cwPreintegrated ? tc + 0.5 * tcStep : tc), viewer);
    float n = float(cwRefine);
    vec4 sum = vec4(0.0);
    float a = front;
    for (int j = 1; j <= cwRefine; ++j) {
        vec3 at = tc + tcStep * (float(j - 1) / n);
        float b = j == cwRefine ? back : volumeAt(tc + tcStep * (float(j) / n));
        vec4 part = classifySlab(a, b, obliquity / n, classLayer(at));
        if (part.a > 0.0)
            sum += (1.0 - sum.a) * shade(part, gradientAt(at + tcStep * (0.5 / n)), viewer);
        a = b;
    }
    return sum;
}

#endif

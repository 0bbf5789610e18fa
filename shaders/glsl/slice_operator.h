// GLSL only: the body of the operator slicing shader (slice_operator.frag.glsl
// and its _id variant). An operator's proxy (paper section 5.1): the fragment
// is a point p' of the deformed space. The probe p0 comes from the operator's
// baked map (Eq. 2, 3, placed by Eq. 8); the feature mask decides between p0,
// p' and nothing (Eq. 4; axis alignment: Eq. 6). The normal is the volume
// gradient carried through the Jacobian of the map (Eq. 5), blended with the
// feature's (Eq. 9, 10) and toward the cut's within the band D (Eq. 7).
#include "glsl/slice_common.h"
#include "shared/feature.h"
#include "shared/operator_frame.h"

layout(location = 0) in vec3 worldPos;
layout(std140, set = 1, binding = 0) uniform Operator {
    OperatorUniforms op;
};
layout(set = 1, binding = 1) uniform sampler3D operatorMap;
// Surface: DT in mm; segment: M; both R16F over the volume's grid. A 1^3
// texture for axis alignment.
layout(set = 1, binding = 2) uniform sampler3D featureTex;

vec4 mapAt(vec3 local) {
    return textureLod(operatorMap, (local - op.mapLo.xyz) / (op.mapHi.xyz - op.mapLo.xyz), 0.0);
}

// xyz: the probe p0 in the world; w: signed distance to the cut (local units).
vec4 probe(vec3 world) {
    vec3 q = (op.worldToLocal * vec4(world, 1.0)).xyz;
    vec4 m = mapAt(q);
    return vec4((op.localToWorld * vec4(q + m.xyz, 1.0)).xyz, m.w);
}

bool inVolume(vec3 tc) {
    return all(greaterThanEqual(tc, vec3(0.0))) && all(lessThanEqual(tc, vec3(1.0)));
}

int alignment() {
    return cwAlignment;
} // op.align.x, fixed per pipeline

// M at texture coordinate tc (0 for axis alignment); `f` receives the
// feature field there (DT or M), which featureGradient reads again.
float maskAt(vec3 tc, out float f) {
    int mode = alignment();
    f = 0.0;
    if (mode == CW_ALIGN_AXIS) return 0.0;
    f = textureLod(featureTex, tc, 0.0).r;
    if (mode == CW_ALIGN_SURFACE) return surfaceMask(f, op.align.y, op.align.z);
    ivec3 dims = textureSize(featureTex, 0);
    ivec3 voxel = clamp(ivec3(floor(tc * vec3(dims))), ivec3(0), dims - 1);
    return segmentMask(f, texelFetch(featureTex, voxel, 0).r >= 0.5);
}

// The feature field's unit gradient (into the feature) at the voxel nearest
// to tc, by central differences over its neighbours: the field stores no
// gradient (2 bytes a voxel instead of 8). Six texel reads cost about what the
// RGBA16F gradient's one filtered fetch did on lavapipe; six filtered fetches
// (a gradient that varies within a voxel) made an operator frame 30 % slower.
vec3 featureDirection(vec3 tc) {
    ivec3 dims = textureSize(featureTex, 0);
    ivec3 v = clamp(ivec3(floor(tc * vec3(dims))), ivec3(0), dims - 1);
    ivec3 lo = max(v - 1, ivec3(0)), hi = min(v + 1, dims - 1);
    vec3 below = vec3(texelFetch(featureTex, ivec3(lo.x, v.y, v.z), 0).r,
                      texelFetch(featureTex, ivec3(v.x, lo.y, v.z), 0).r,
                      texelFetch(featureTex, ivec3(v.x, v.y, lo.z), 0).r);
    vec3 above = vec3(texelFetch(featureTex, ivec3(hi.x, v.y, v.z), 0).r,
                      texelFetch(featureTex, ivec3(v.x, hi.y, v.z), 0).r,
                      texelFetch(featureTex, ivec3(v.x, v.y, hi.z), 0).r);
    return featureGradientOf(below, above, op.featureScale.xyz);
}

struct Resolved {
    int which;     // CW_CASE_*
    vec3 tc;       // texture coordinate of p (transformed or masked)
    float cutW;    // the map's signed cut distance at p'
    float feature; // the feature field at tc (alignment other than axis)
    float m0;      // the mask M at p0 and at p' (0 with axis alignment)
    float mPrime;
};

// Eq. 3 and 4 for the point p' = world.
Resolved resolve(vec3 world) {
    vec4 p0 = probe(world);
    vec3 tc0 = toTexture(p0.xyz);
    vec3 tcPrime = toTexture(world);
    bool p0Valid = p0.w > 0.0 && inVolume(tc0);
    bool primeIn = inVolume(tcPrime);
    float f0, fPrime;
    float m0 = maskAt(tc0, f0);
    float mPrime = maskAt(tcPrime, fPrime);
    Resolved r;
    r.which = featureCase(p0Valid, p0Valid ? m0 : 0.0, primeIn, primeIn ? mPrime : 0.0);
    bool masked = r.which == CW_CASE_MASKED;
    r.tc = masked ? tcPrime : tc0;
    r.feature = masked ? fPrime : f0;
    r.cutW = p0.w;
    r.m0 = m0;
    r.mPrime = mPrime;
    return r;
}

// The source-space gradient at p (data gradient, with Eq. 9 / 10 applied);
// f is the feature field at p, whose texture coordinate is tc.
vec4 featureGradient(vec4 g, float f, vec3 tc, bool moved) {
    int mode = alignment();
    if (mode == CW_ALIGN_AXIS) return g;
    if (mode == CW_ALIGN_SURFACE) {
        float beta = surfaceBeta(f, op.align.y, op.align.z);
        if (beta == 0.0) return g;
        return vec4(surfaceNormal(g.xyz, featureDirection(tc), beta), mix(g.w, 1.0, abs(beta)));
    }
    // Segment: only moved points (M < 0.5) change. Near the segment the data
    // gradient gives way to the segment-aware one (into the segment), which
    // Eq. 10 turns over as M approaches 0.5.
    float m = f;
    float gamma = segmentGamma(m);
    if (!moved || gamma == 0.0) return g;
    vec3 toward = mix(g.xyz, featureDirection(tc), clamp(2.0 * m, 0.0, 1.0));
    return vec4(segmentNormal(toward, gamma), mix(g.w, 1.0, clamp(2.0 * m, 0.0, 1.0)));
}

// For a slab with one end `v` kept and the other `e` empty: the quantity
// whose sign change emptied e, at v (> 0) and at e (<= 0 when it explains e):
// w for a cut, 0.5 - M at p0 where the feature stays behind, M at p' - 0.5
// where the feature left in place ends.
vec2 presence(Resolved v, Resolved e) {
    if (v.which == CW_CASE_MASKED) return vec2(v.mPrime - 0.5, e.mPrime - 0.5);
    if (e.cutW <= 0.0) return vec2(v.cutW, e.cutW);
    return vec2(0.5 - v.m0, 0.5 - e.m0);
}

// The part of such a slab that is kept: the quantity is linear across a slab,
// so the material ends where it crosses 0. Clipping the slab instead of
// keeping or dropping it whole stops a cut face (or the face the feature left)
// from showing the slices as contour lines. `otherwise` where the quantity
// does not explain the empty end (outside the volume). Pre-integrated only:
// post-classified slices have no back.
float keptFraction(vec2 q, float otherwise) {
    if (q.y > 0.0) return otherwise;
    return clamp(q.x / max(q.x - q.y, 1e-6), 0.0, 1.0);
}

// The antiderivative of clamp(w / d, 0, 1).
float rampIntegral(float w, float d) {
    float c = clamp(w, 0.0, d);
    return c * c / (2.0 * d) + max(w - d, 0.0);
}

// The mean of clamp(w / d, 0, 1) over a slab where w runs linearly from a to
// b: Eq. 7's weight for the whole slab, not at one point of it. A band of a
// slice or two would otherwise show the slices as steps of shading.
float bandMean(float a, float b, float d) {
    if (abs(b - a) < 1e-4 * d) return clamp(0.5 * (a + b) / d, 0.0, 1.0);
    return (rampIntegral(b, d) - rampIntegral(a, d)) / (b - a);
}

void main() {
    vec3 toEye = toEyeFrom(worldPos);
    float obliquity = obliquityOf(toEye);
    float stepMm = u.viewDir.w * obliquity;
    Resolved front = resolve(worldPos);
    bool frontEmpty = front.which == CW_CASE_EMPTY;
    if (frontEmpty && !cwPreintegrated) {
        emit(vec4(0.0), 0.0); // a cut, an opening, the feature's place, or nothing
        return;
    }
    Resolved middle = front; // where the slab is shaded
    float frontValue = 0.0, backValue = 0.0;
    float kept = 1.0;    // the fraction of the slab the cut leaves
    float shadeAt = 0.0; // where along the slab (0 front, 1 back) it is shaded
    float wNear = front.cutW, wFar = front.cutW; // w at the ends of the kept part
    if (!frontEmpty) frontValue = backValue = textureLod(volumeTex, front.tc, 0.0).r;
    if (cwPreintegrated) {
        Resolved back = resolve(worldPos - toEye * stepMm);
        bool backEmpty = back.which == CW_CASE_EMPTY;
        shadeAt = 0.5;
        if (frontEmpty) { // the slab enters the material through a face
            if (backEmpty) {
                emit(vec4(0.0), 0.0);
                return;
            }
            kept = keptFraction(presence(back, front), 0.0);
            middle = back;
            bool cut = back.which == CW_CASE_TRANSFORMED && front.cutW <= 0.0;
            wNear = cut ? 0.0 : back.cutW;
            wFar = back.cutW;
            frontValue = backValue = textureLod(volumeTex, back.tc, 0.0).r;
            shadeAt = 1.0 - 0.5 * kept;
        } else if (backEmpty) { // it leaves the material through a face
            kept = keptFraction(presence(front, back), 1.0);
            bool cut = front.which == CW_CASE_TRANSFORMED && back.cutW <= 0.0;
            wFar = cut ? 0.0 : front.cutW;
            shadeAt = 0.5 * kept;
        } else {
            backValue = textureLod(volumeTex, back.tc, 0.0).r;
            if (back.which == front.which) { // the middle, halfway: exact where the map is affine
                middle.tc = 0.5 * (front.tc + back.tc);
                middle.feature = 0.5 * (front.feature + back.feature);
                wFar = back.cutW;
            }
        }
    }
    if (kept <= 0.0) {
        emit(vec4(0.0), 0.0);
        return;
    }
    bool masked = middle.which == CW_CASE_MASKED;
    float layer = classLayer(middle.tc);
    vec3 shadePoint = worldPos - toEye * (shadeAt * stepMm);
    vec4 c = classifySlab(frontValue, backValue, obliquity * kept, layer);
    if (c.a <= 0.0) {
        emit(vec4(0.0), 0.0);
        return;
    }

    // One gradient fetch and one feature gradient for both cases below: on
    // SIMD CPUs both sides of a branch run, so a call in each would cost twice.
    vec4 g = featureGradient(textureLod(gradientTex, middle.tc, 0.0), middle.feature, middle.tc,
                             !masked);
    if (masked) { // p = p': the volume's own gradient (Eq. 5), with Eq. 9's blend
        vec4 n = vec4(dot(g.xyz, g.xyz) > 1e-12 ? normalize(g.xyz) : vec3(0.0), g.w);
        emit(shade(c, n, toEye), CW_ID_BACKGROUND);
        return;
    }

    // Jacobian of the continuous backward map and gradient of the cut distance,
    // by central differences over one texel of the map.
    vec3 q = (op.worldToLocal * vec4(shadePoint, 1.0)).xyz;
    float h = op.mapHi.w;
    mat3 jacobian;
    vec3 cutGradient;
    for (int i = 0; i < 3; ++i) {
        vec3 e = vec3(0.0);
        e[i] = h;
        vec4 d = (mapAt(q + e) - mapAt(q - e)) / (2.0 * h);
        vec3 column = d.xyz;
        column[i] += 1.0;
        jacobian[i] = column;
        cutGradient[i] = d.w;
    }
    mat3 a = mat3(op.localToWorld);
    mat3 aInvT = transpose(mat3(op.worldToLocal));
    vec3 carried = aInvT * (transpose(jacobian) * (transpose(a) * g.xyz)); // Eq. 5
    vec3 cut = aInvT * cutGradient; // points into the material
    float omega = op.band.x > 0.0 ? 1.0 - bandMean(wNear, wFar, op.band.x) : 0.0;
    vec4 gradient = vec4(dot(carried, carried) > 1e-12 ? normalize(carried) : vec3(0.0), g.w);
    if (omega > 0.0 && dot(cut, cut) > 1e-12) { // Eq. 7
        vec3 blended = mix(gradient.xyz, normalize(cut), omega);
        gradient = vec4(dot(blended, blended) > 1e-12 ? normalize(blended) : normalize(cut),
                        mix(g.w, 1.0, omega));
    }
    emit(shade(c, gradient, toEye), op.band.y);
}

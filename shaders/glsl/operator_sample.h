// GLSL only: what an operator does to one slab of the deformed space, shared
// by the operator slicing shader (slice_operator.h) and the ray caster
// (raycast_operators.comp.glsl). A point p' of the deformed space takes the
// probe p0 from the operator's baked map (Eq. 2, 3, placed by Eq. 8); the
// feature mask decides between p0, p' and nothing (Eq. 4; axis alignment:
// Eq. 6). The normal is the volume gradient carried through the Jacobian of
// the map (Eq. 5), blended with the feature's (Eq. 9, 10) and toward the
// cut's within the band D (Eq. 7).
//
// Every function takes the operator it works for: its uniforms `op`, its slot
// (0 in the slicing shader; the ray caster's 0..CW_RAY_MAX_OPERATORS - 1), its
// baked `map`, its `feature` field (surface: DT in mm, R16F over the volume's
// grid; segment: RG16F over the operator's region of it, M and the value
// moved material reads, bake/feature_region.hpp; a 1^3 texture for axis
// alignment) and its alignment
// `mode` (CW_ALIGN_*, a constant of the pipeline, so the compiler drops the
// other modes' code).
#ifndef CUTAWAY_OPERATOR_SAMPLE_H
#define CUTAWAY_OPERATOR_SAMPLE_H

#include "glsl/sample_common.h"
#include "shared/feature.h"
#include "shared/feature_bake.h"
#include "shared/operator_frame.h"

vec4 mapAt(OperatorUniforms op, sampler3D map, vec3 local) {
    return textureLod(map, (local - op.mapLo.xyz) / (op.mapHi.xyz - op.mapLo.xyz), 0.0);
}

// xyz: the probe p0 in the world; w: signed distance to the cut (local units).
vec4 probe(OperatorUniforms op, sampler3D map, vec3 world) {
    vec3 q = (op.worldToLocal * vec4(world, 1.0)).xyz;
    vec4 m = mapAt(op, map, q);
    return vec4((op.localToWorld * vec4(q + m.xyz, 1.0)).xyz, m.w);
}

bool inVolume(vec3 tc) {
    return all(greaterThanEqual(tc, vec3(0.0))) && all(lessThanEqual(tc, vec3(1.0)));
}

// The feature field on the volume's grid (surface alignment's DT; segment
// alignment's M, whose region the sampled `feature` holds instead; axis
// alignment's 1^3 zero) again as a storage image, one per operator slot: the
// slicing shader's set 1, the ray caster's sets 1 + slot. With cwStorageFetch
// (CPU devices) surface alignment loads its texels and filters them here, as
// volumeAt does the values': on lavapipe a sampled R16F fetch is a call that
// gathers its texels lane by lane.
#ifdef CW_STORAGE_PATHS
layout(set = 1, binding = CW_BIND_OP_FEATURE_IMAGE, r16f) uniform readonly image3D featureImage0;
#ifdef CW_RAY_OPERATORS
layout(set = 2, binding = CW_BIND_OP_FEATURE_IMAGE, r16f) uniform readonly image3D featureImage1;
layout(set = 3, binding = CW_BIND_OP_FEATURE_IMAGE, r16f) uniform readonly image3D featureImage2;
#endif
#endif

// Whether the feature field's texels are loaded (featureTexel) instead of
// sampled from `feature`.
bool featureLoaded(int mode) {
    return cwStorageFetch != 0 && mode == CW_ALIGN_SURFACE;
}

// Slot `slot`'s feature image's size and its texel at `voxel` (within the
// size). GLSL takes no image with a format as a parameter; each call passes
// a constant slot, so the compiler keeps one image (as blockAt does). Built
// without CW_STORAGE_PATHS, featureLoaded is false and these are never called.
ivec3 featureImageSize(int slot) {
#ifdef CW_STORAGE_PATHS
#ifdef CW_RAY_OPERATORS
    if (slot == 1) return imageSize(featureImage1);
    if (slot == 2) return imageSize(featureImage2);
#endif
    return imageSize(featureImage0);
#else
    return ivec3(1);
#endif
}

float featureTexel(int slot, ivec3 voxel) {
#ifdef CW_STORAGE_PATHS
#ifdef CW_RAY_OPERATORS
    if (slot == 1) return imageLoad(featureImage1, voxel).r;
    if (slot == 2) return imageLoad(featureImage2, voxel).r;
#endif
    return imageLoad(featureImage0, voxel).r;
#else
    return 0.0;
#endif
}

// The feature field at feature coordinate `at`, loaded: trilinear, clamped to
// the edge, as the sampler filters it.
float featureFiltered(int slot, vec3 at) {
    Trilinear t = trilinearAt(at, featureImageSize(slot));
    ivec3 lo = t.lo, hi = t.hi;
    vec4 near =
        vec4(featureTexel(slot, lo), featureTexel(slot, ivec3(hi.x, lo.yz)),
             featureTexel(slot, ivec3(lo.x, hi.y, lo.z)), featureTexel(slot, ivec3(hi.xy, lo.z)));
    vec4 far =
        vec4(featureTexel(slot, ivec3(lo.xy, hi.z)), featureTexel(slot, ivec3(hi.x, lo.y, hi.z)),
             featureTexel(slot, ivec3(lo.x, hi.yz)), featureTexel(slot, hi));
    return weighTexels(t.f, near, far);
}

// The feature field (r: DT or M; g: the value moved material reads) at
// feature coordinate `at` by /render/filter "cubic": Catmull-Rom over the
// 4^3 texels around it, held to the range of its cell's eight as volumeAt's
// values are (so the field ranges' skipping holds).
vec2 featureCubic(sampler3D feature, int slot, int mode, vec3 at) {
    bool loaded = featureLoaded(mode);
    CubicCell c = cubicCell(at, loaded ? featureImageSize(slot) : textureSize(feature, 0));
    vec2 sum = vec2(0.0), lo = vec2(1e30), hi = vec2(-1e30);
    for (int z = 0; z < 4; ++z)
        for (int y = 0; y < 4; ++y) {
            vec2 row = vec2(0.0);
            for (int x = 0; x < 4; ++x) {
                ivec3 p = ivec3(c.ix[x], c.iy[y], c.iz[z]);
                vec2 v = loaded ? vec2(featureTexel(slot, p), 0.0) : texelFetch(feature, p, 0).rg;
                row += c.wx[x] * v;
                if (inCubicCell(x, y, z)) {
                    lo = min(lo, v);
                    hi = max(hi, v);
                }
            }
            sum += (c.wz[z] * c.wy[y]) * row;
        }
    return clamp(sum, lo, hi);
}

// The feature texture's coordinate of the volume's texture coordinate tc.
vec3 featureTcOf(OperatorUniforms op, vec3 tc) {
    return tc * op.featureTc.xyz + op.featureTc0.xyz;
}

// M at texture coordinate tc (0 for axis alignment); `f` receives the
// feature field there (DT or M), which featureGradient reads again, and
// `moving` the value moved material reads there (segment alignment). With
// `keepVoxels` every voxel of a segment counts as feature (segmentMask).
float maskAt(OperatorUniforms op, sampler3D feature, int slot, int mode, vec3 tc, bool keepVoxels,
             out float f, out float moving) {
    f = 0.0;
    moving = 0.0;
    if (mode == CW_ALIGN_AXIS) return 0.0;
    vec3 at = featureTcOf(op, tc);
    if (featureLoaded(mode) && !cwCubic) {
        f = featureFiltered(slot, at);
        return surfaceMask(f, op.align.y, op.align.z);
    }
    vec2 texel = cwCubic ? featureCubic(feature, slot, mode, at) : textureLod(feature, at, 0.0).rg;
    f = texel.r;
    if (mode == CW_ALIGN_SURFACE) return surfaceMask(f, op.align.y, op.align.z);
    moving = texel.g;
    if (!keepVoxels) return f;
    ivec3 dims = textureSize(feature, 0);
    ivec3 voxel = clamp(ivec3(floor(at * vec3(dims))), ivec3(0), dims - 1);
    return segmentMask(f, maskInside(texelFetch(feature, voxel, 0).r));
}

// The feature field's unit gradient (into the feature) at tc, by central
// differences of the filtered field a voxel either side: the field stores no
// gradient (2 bytes a voxel instead of 8). Taken at the voxel nearest to tc
// (six texel reads, the cost of one filtered fetch on lavapipe) it was
// constant over each voxel, and the light on a flap's underside and on the
// surface it bares showed the voxels as a lattice; six filtered fetches cost
// whole processes of the aligned gallery scenes 1.0-1.2x (docs/quality.md).
vec3 featureDirection(OperatorUniforms op, sampler3D feature, int slot, int mode, vec3 tc) {
    ivec3 dims = featureLoaded(mode) ? featureImageSize(slot) : textureSize(feature, 0);
    vec3 at = featureTcOf(op, tc);
    vec3 h = 1.0 / vec3(dims);
    vec3 below, above;
    for (int i = 0; i < 3; ++i) {
        vec3 d = vec3(0.0);
        d[i] = h[i];
        below[i] = featureLoaded(mode) ? featureFiltered(slot, at - d)
                                       : textureLod(feature, at - d, 0.0).r;
        above[i] = featureLoaded(mode) ? featureFiltered(slot, at + d)
                                       : textureLod(feature, at + d, 0.0).r;
    }
    return featureGradientOf(below, above, op.featureScale.xyz);
}

// The footprint, in mm, over which a cut's coverage is taken at `world`
// (FrameUniforms.termination; 0 with /render/cut_antialias 0).
float footprintMm(vec3 world) {
    return u.termination.y + u.termination.z * max(dot(world - u.eye.xyz, u.viewDir.xyz), 0.0);
}

// How far beyond the cut (in units of w) a sample of footprint `footprint`
// (footprintMm) may still show
// part of the material: half the most w can spread over the footprint on a
// surface seen down to about 15 degrees (cutCovered), at most a texel of the
// map (OperatorUniforms.mapLo.w).
float cutMargin(OperatorUniforms op, float footprint) {
    return min(2.0 * footprint * op.band.w, op.mapLo.w);
}

struct Resolved {
    int which;     // CW_CASE_*
    vec3 tc;       // texture coordinate of p (transformed or masked)
    float value;   // the volume there
    float cutW;    // the map's signed cut distance at p'
    float shift;   // how far the map moves material to p', in texels of the map
    float feature; // the feature field at tc (alignment other than axis)
    float m0;      // the mask M at p0 and at p' (0 with axis alignment)
    float mPrime;
    float margin; // cutMargin at p': p0 counts as kept where w > -margin
};

// Eq. 3 and 4 for the point p' = world, and the volume's value at p (fetched
// for an empty point too: on lavapipe a branch around it would cost as much,
// and the ray caster keeps the value as the next slab's front). With segment
// alignment a point that moves reads the feature texture's value instead
// (the segment's own values taken out; feature_bake.h, movedValue), which
// the mask's fetch at p0 brings along.
Resolved resolve(OperatorUniforms op, sampler3D map, sampler3D feature, int slot, int mode,
                 vec3 world) {
    vec4 p0 = probe(op, map, world);
    vec3 tc0 = toTexture(p0.xyz);
    vec3 tcPrime = toTexture(world);
    float margin = cutMargin(op, footprintMm(world));
    bool p0Valid = p0.w > -margin && inVolume(tc0);
    bool primeIn = inVolume(tcPrime);
    float f0, fPrime, moving0, movingPrime;
    // A point stays where a voxel of the segment is nearest, as outside the
    // box (no seam at its faces). Its material leaves with the operator
    // unless the smoothed segment holds it, so a flap's underside follows the
    // segment's smooth 0.5 surface, not its voxels' staircase (a lattice in
    // the light); where labels classify, no voxel of the segment may leave,
    // or it would take the segment's colours along.
    float m0 = maskAt(op, feature, slot, mode, tc0, cwByLabel, f0, moving0);
    float mPrime = maskAt(op, feature, slot, mode, tcPrime, true, fPrime, movingPrime);
    Resolved r;
    r.which = featureCase(p0Valid, p0Valid ? m0 : 0.0, primeIn, primeIn ? mPrime : 0.0);
    bool masked = r.which == CW_CASE_MASKED;
    r.tc = masked ? tcPrime : tc0;
    if (mode == CW_ALIGN_SEGMENT) {
        float kept = volumeAt(tcPrime);
        r.value = masked ? kept : moving0;
    } else {
        r.value = volumeAt(r.tc);
    }
    r.feature = masked ? fPrime : f0;
    r.cutW = p0.w;
    r.shift = length((op.worldToLocal * vec4(p0.xyz - world, 0.0)).xyz) / op.mapHi.w;
    r.m0 = m0;
    r.mPrime = mPrime;
    r.margin = margin;
    return r;
}

// How much the feature's break is there at a point: Eq. 9 and 10 turn the
// normal toward the feature where material above it moved off or was cut
// away, so only where the map moves material (by a texel or more) or near a
// cut (within the band D, fading out over another D). Elsewhere in the box
// nothing parts at the feature, and the volume's own normal is right: an
// operator that moves nothing then renders as no operator, and a box whose
// displacement fades to 0 at its faces shows no seam there.
float breakWeight(OperatorUniforms op, Resolved r) {
    float band = max(op.band.x, op.mapHi.w);
    return max(clamp(r.shift, 0.0, 1.0), clamp(2.0 - r.cutW / band, 0.0, 1.0));
}

// The source-space gradient at p (data gradient, with Eq. 9 / 10 applied);
// f is the feature field at p, whose texture coordinate is tc; `weight` the
// break's (breakWeight).
vec4 featureGradient(OperatorUniforms op, sampler3D feature, int slot, int mode, vec4 g, float f,
                     vec3 tc, bool moved, float weight) {
    if (mode == CW_ALIGN_AXIS) return g;
    if (mode == CW_ALIGN_SURFACE) {
        float beta = weight * surfaceBeta(f, op.align.y, op.align.z);
        if (beta == 0.0) return g;
        return vec4(surfaceNormal(g.xyz, featureDirection(op, feature, slot, mode, tc), beta),
                    mix(g.w, 1.0, abs(beta)));
    }
    // Segment: only moved points (M < 0.5) change. Near the segment the data
    // gradient gives way to the segment-aware one (into the segment), which
    // Eq. 10 turns over as M approaches 0.5.
    float m = f;
    float gamma = segmentGamma(m);
    if (!moved || gamma == 0.0) return g;
    vec3 toward =
        mix(g.xyz, featureDirection(op, feature, slot, mode, tc), clamp(2.0 * m, 0.0, 1.0));
    return vec4(segmentNormal(toward, gamma), mix(g.w, 1.0, clamp(2.0 * m, 0.0, 1.0)));
}

// For a slab with one end `v` kept and the other `e` empty: the quantity
// whose sign change emptied e, at v (> 0) and at e (<= 0 when it explains e):
// w beyond the margin for a cut, 0.5 - M at p0 where the feature stays
// behind, M at p' - 0.5 where the feature left in place ends.
vec2 presence(Resolved v, Resolved e) {
    if (v.which == CW_CASE_MASKED) return vec2(v.mPrime - 0.5, e.mPrime - 0.5);
    if (e.cutW <= -e.margin) return vec2(v.cutW + e.margin, e.cutW + e.margin);
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

// The share of a slab of kept, moved material (w from wNear to wFar) that
// lies in the cut face's layer, 0 < w < its depth (OperatorUniforms.cutFace,
// band.z): the mean over the slab, softened over a tenth of the depth, so
// the layer's inner edge shows no slices.
float cutFaceShare(OperatorUniforms op, float wNear, float wFar) {
    float depth = op.band.z;
    return bandMean(depth - wNear, depth - wFar, 0.1 * depth);
}

// What the operator makes of the slab from p' (resolved `front`) to the next
// plane along the ray (`back`; post-classified frames have no back and pass
// the front again): the values it classifies, the part the cut leaves, and
// where it is shaded.
struct Slab {
    bool empty; // nothing shows: a cut, an opening, the feature's place
    Resolved middle;
    float frontValue, backValue;
    float kept;        // the fraction of the slab the cut leaves
    float shadeAt;     // where along the slab (0 front, 1 back) it is shaded
    float wNear, wFar; // w at the ends of the kept part
};

Slab operatorSlab(int mode, Resolved front, Resolved back) {
    Slab s;
    bool frontEmpty = front.which == CW_CASE_EMPTY;
    s.empty = frontEmpty;
    s.middle = front;
    s.frontValue = s.backValue = frontEmpty ? 0.0 : front.value;
    s.kept = 1.0;
    s.shadeAt = 0.0;
    s.wNear = s.wFar = front.cutW;
    if (!cwPreintegrated) return s;
    bool backEmpty = back.which == CW_CASE_EMPTY;
    s.shadeAt = 0.5;
    if (frontEmpty) { // the slab enters the material through a face
        if (backEmpty) return s;
        s.empty = false;
        s.kept = keptFraction(presence(back, front), 0.0);
        s.middle = back;
        bool cut = back.which == CW_CASE_TRANSFORMED && front.cutW <= -front.margin;
        s.wNear = cut ? -front.margin : back.cutW;
        s.wFar = back.cutW;
        s.frontValue = s.backValue = back.value;
        s.shadeAt = 1.0 - 0.5 * s.kept;
    } else if (backEmpty) { // it leaves the material through a face
        s.kept = keptFraction(presence(front, back), 1.0);
        bool cut = front.which == CW_CASE_TRANSFORMED && back.cutW <= -back.margin;
        s.wFar = cut ? -back.margin : front.cutW;
        s.shadeAt = 0.5 * s.kept;
    } else {
        s.backValue = back.value;
        // The middle, halfway: exact where the map is affine, and where the
        // slab crosses from material that moves to material kept in place
        // (or back) where the map moves nothing (both ends resolve near p').
        // Shaded at its front there, a slab across the feature's surface lit
        // the skin over it a half slab off: a speckle where nothing moved.
        // Not with segment alignment: there the two sides read different
        // values even where nothing moves, and its rims stayed crisper.
        bool contiguous = mode != CW_ALIGN_SEGMENT && max(front.shift, back.shift) < 0.25;
        if (back.which == front.which || contiguous) {
            s.middle.tc = 0.5 * (front.tc + back.tc);
            s.middle.feature = 0.5 * (front.feature + back.feature);
            s.wFar = back.cutW;
        }
    }
    s.empty = s.empty || s.kept <= 0.0;
    return s;
}

// The map's derivative along local axis `axis` at local point q: section
// `axis` of the operator's `derivatives` (bake/operator_bake.hpp, at half
// the map's resolution over the same box), clamped to the section's texel
// centres along x as the sampler clamps y and z. One fetch where a central
// difference of the map took two.
vec4 mapDerivative(OperatorUniforms op, sampler3D derivatives, vec3 q, int axis) {
    vec3 tc = (q - op.mapLo.xyz) / (op.mapHi.xyz - op.mapLo.xyz);
    float width = float(textureSize(derivatives, 0).x) / 3.0; // a section's texels along x
    tc.x = (clamp(tc.x * width, 0.5, width - 0.5) + float(axis) * width) / (3.0 * width);
    return textureLod(derivatives, tc, 0.0);
}

// The slab's premultiplied colour before lighting (Slab s, `obliquity` as
// classifySlab takes it), with the cut face's colour mixed in; 0 when nothing
// shows.
vec4 operatorSlabColor(OperatorUniforms op, Slab s, float obliquity) {
    if (s.empty) return vec4(0.0);
    bool masked = s.middle.which == CW_CASE_MASKED;
    vec4 c = classifySlab(s.frontValue, s.backValue, obliquity * s.kept, classLayer(s.middle.tc));
    if (c.a <= 0.0) return vec4(0.0);
    if (op.cutFace.w > 0.0 && !masked) // premultiplied: the face's colour times the opacity
        c.rgb = mix(c.rgb, op.cutFace.rgb * c.a, op.cutFace.w * cutFaceShare(op, s.wNear, s.wFar));
    return c;
}

// The opacity of material of normalized value `value` over `mm` (the
// transfer function at tc's layer; 0 when post-classified, whose table has
// no slab of one value).
float opacityOver(float value, float mm, vec3 tc) {
    if (!cwPreintegrated) return 0.0;
    return classifySlab(value, value, mm / u.viewDir.w, classLayer(tc)).a;
}

// The slab's colour `c` (premultiplied) times the share of the pixel's
// footprint that the cut leaves, over the kept part of slab `s` (w from
// s.wNear to s.wFar). `cut` is w's gradient (per mm), `ray` the unit ray,
// `surface` the data's unit normal there and how much of a surface it is.
// Across the footprint w spreads by the footprint's width times its gradient
// across the ray; where the pixel sees a surface, a neighbouring ray meets
// it nearer or farther, which a slanted surface stretches (the gradient
// along the surface instead). Held to twice the margin. The material shows
// where w > 0, a share clamp(0.5 + w / spread, 0, 1) of the footprint.
// Translucent material takes the mean share over the slab. Where the
// material in front (at the slab's front, over the slab's length) is
// opaque, the part of the footprint that met it is spent, and the slab
// adds only the share it adds (what its back leaves beyond its front):
// taken as the mean at every slab, a pixel at the edge of an opaque cut
// took its share again at each slab behind the surface and came out nearly
// opaque. Compositing keeps no memory along the ray (the slicer blends
// slabs in the framebuffer), so which material counts as spent is judged
// slab by slab: a finer slice spacing moves an edge by up to half a pixel
// (docs/quality.md). A cut's edge seen at a slant so is straight and
// smooth where each pixel's ray alone would decide in steps. `stepMm`: the
// slab's length.
vec4 cutCovered(OperatorUniforms op, Slab s, vec4 c, vec3 cut, vec3 ray, vec4 surface, vec3 world,
                float stepMm) {
    float footprint = footprintMm(world);
    if (footprint <= 0.0 || c.a <= 0.0) return c;
    float facing = dot(ray, surface.xyz);
    facing = facing < 0.0 ? min(facing, -0.05) : max(facing, 0.05);
    vec3 g = cut - surface.xyz * (surface.w * dot(cut, ray) / facing);
    vec3 across = g - dot(g, ray) * ray;
    float half_ = 0.5 * min(footprint * length(across), 2.0 * cutMargin(op, footprint));
    if (min(s.wNear, s.wFar) >= half_) return c;
    float spread = max(2.0 * half_, 1e-6);
    float near = s.wNear + half_, far = s.wFar + half_;
    float hi = max(near, far), lo = min(near, far);
    if (hi <= 0.0) return vec4(0.0);
    // The slab's opacity over the part where the share is above 0.
    float alpha = correctOpacity(c.a, keptFraction(vec2(hi, lo), 1.0));
    float mean = bandMean(max(lo, 0.0), hi, spread);
    float atNear = clamp(near / spread, 0.0, 1.0);
    float added = max(clamp(far / spread, 0.0, 1.0) - atNear, 0.0) / max(1.0 - atNear, 1e-3);
    float opaque = opacityOver(s.frontValue, stepMm, s.middle.tc);
    return c * (alpha * mix(mean, added, opaque) / c.a);
}

// The slab's colour `c` (operatorSlabColor) lit; `world` is p' (the slab's
// front), seen from `viewer` (viewerOf), `stepMm` the slab's length along
// the ray toward -viewer.toEye.
vec4 lightOperatorSlab(OperatorUniforms op, sampler3D derivatives, sampler3D feature, int slot,
                       int mode, Slab s, vec4 c, vec3 world, Viewer viewer, float stepMm) {
    bool masked = s.middle.which == CW_CASE_MASKED;
    vec3 shadePoint = world - viewer.toEye * (s.shadeAt * stepMm);
    // One gradient fetch and one feature gradient for both cases below: on
    // SIMD CPUs both sides of a branch run, so a call in each would cost twice.
    vec4 g = featureGradient(op, feature, slot, mode, gradientAt(s.middle.tc), s.middle.feature,
                             s.middle.tc, !masked, breakWeight(op, s.middle));
    // p = p': the volume's own gradient (Eq. 5), with Eq. 9's blend. Moved
    // points carry it through the map's Jacobian instead; both are lit by one
    // call below (lavapipe runs both sides of a branch: a call in each lit
    // every slab twice).
    vec4 n = vec4(dot(g.xyz, g.xyz) > 1e-12 ? normalize(g.xyz) : vec3(0.0), g.w);
    if (!masked) {
        // Jacobian of the continuous backward map and gradient of the cut
        // distance, by central differences over one texel of the map
        // (baked: mapDerivative).
        vec3 q = (op.worldToLocal * vec4(shadePoint, 1.0)).xyz;
        mat3 jacobian;
        vec3 cutGradient;
        for (int i = 0; i < 3; ++i) {
            vec4 d = mapDerivative(op, derivatives, q, i);
            vec3 column = d.xyz;
            column[i] += 1.0;
            jacobian[i] = column;
            cutGradient[i] = d.w;
        }
        mat3 a = mat3(op.localToWorld);
        mat3 aInvT = transpose(mat3(op.worldToLocal));
        vec3 carried = aInvT * (transpose(jacobian) * (transpose(a) * g.xyz)); // Eq. 5
        vec3 cut = aInvT * cutGradient; // points into the material
        float omega = op.band.x > 0.0 ? 1.0 - bandMean(s.wNear, s.wFar, op.band.x) : 0.0;
        n = vec4(dot(carried, carried) > 1e-12 ? normalize(carried) : vec3(0.0), g.w);
        c = cutCovered(op, s, c, cut, -viewer.toEye, vec4(n.xyz, smoothstep(0.05, 0.25, g.w)),
                       shadePoint, stepMm);
        if (omega > 0.0 && dot(cut, cut) > 1e-12) { // Eq. 7
            vec3 blended = mix(n.xyz, normalize(cut), omega);
            n = vec4(dot(blended, blended) > 1e-12 ? normalize(blended) : normalize(cut),
                     mix(g.w, 1.0, omega));
        }
    }
    return shade(c, n, viewer);
}

// The premultiplied, shaded colour of the slab from p' = `world` (resolved
// `front`) to world + step (`back`; post-classified frames pass the front
// again), seen from `viewer`; `stepMm` is the length of `step`. A slab that
// shows (refines) is taken in cwRefine sub-slabs, each resolved at its ends,
// cut, classified and lit on its own and composited front to back: a slab
// across a cut, a flap's stretched material or the face the feature left
// is where one slab's approximations show most. `moved`: whether the colour
// came from a point that moved with the operator (not the feature left in
// place): the first sub-slab's that brings the slab to CW_ID_MIN_ALPHA.
// `source`: the texture coordinate that sub-slab's material came from (its
// label names the slab's in the label channels).
vec4 refinedOperatorSlab(OperatorUniforms op, sampler3D map, sampler3D derivatives,
                         sampler3D feature, int slot, int mode, Resolved front, Resolved back,
                         vec3 world, vec3 step, Viewer viewer, float obliquity, float stepMm,
                         out bool moved, out vec3 source) {
    Slab s = operatorSlab(mode, front, back);
    vec4 c = operatorSlabColor(op, s, obliquity);
    moved = !s.empty && s.middle.which != CW_CASE_MASKED;
    source = s.middle.tc;
    if (c.a <= 0.0) return vec4(0.0);
    if (!refines())
        return lightOperatorSlab(op, derivatives, feature, slot, mode, s, c, world, viewer, stepMm);
    float n = float(cwRefine);
    vec4 sum = vec4(0.0);
    Resolved a = front;
    bool named = false;
    for (int j = 1; j <= cwRefine; ++j) {
        vec3 at = world + step * (float(j - 1) / n);
        Resolved b = j == cwRefine
                         ? back
                         : resolve(op, map, feature, slot, mode, world + step * (float(j) / n));
        Slab part = operatorSlab(mode, a, b);
        vec4 pc = operatorSlabColor(op, part, obliquity / n);
        if (pc.a > 0.0)
            sum += (1.0 - sum.a) * lightOperatorSlab(op, derivatives, feature, slot, mode, part, pc,
                                                     at, viewer, stepMm / n);
        if (!named && sum.a >= CW_ID_MIN_ALPHA) {
            moved = part.middle.which != CW_CASE_MASKED;
            source = part.middle.tc;
            named = true;
        }
        a = b;
    }
    return sum;
}

#endif

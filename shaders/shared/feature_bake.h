// The feature-alignment bakes (paper sections 4.2 and 4.3), shared by their
// compute shaders and the CPU twins in bake/feature_bake.cpp.
//
// Distance field DT: an exact Euclidean distance transform done separably
// (Meijster et al.; Felzenszwalb and Huttenlocher): edt_lines finds, along x,
// the distance to the nearest background voxel; edt_envelope then takes,
// along y and then z, the lower envelope of the parabolas
// f(q) + (spacing * (p - q))^2, f the squared distance in mm^2 (kEdtFar
// stands for "no background on this line", +infinity). Every pass works in
// place in the R16F field the renderer samples and stores the distance in mm
// (kHalfMax: infinite): no 4-byte scratch image, and each pass rounds to half
// precision (2^-11 relative), three times in all.
//
// Mask M: the segment indicator smoothed by a separable Gaussian (mask_blur,
// one axis per pass), then encoded by maskEncode.
//
// field_finish encodes M in place. The field's gradient is not stored: the operator shader takes
// it by central differences where it needs it (featureGradientOf in feature.h),
// which keeps the field at 2 bytes per voxel instead of 8.
#ifndef CUTAWAY_FEATURE_BAKE_H
#define CUTAWAY_FEATURE_BAKE_H

#include "shared/glsl_cpp.h"

CW_NAMESPACE_BEGIN

#ifdef __cplusplus
using glm::exp;
#endif

// Longest line the distance transform handles (the envelope's private arrays).
const int kEdtMaxLine = 1024;
// Squared distance standing for +infinity; anything >= kEdtInfinite is infinite.
const float kEdtFar = 1.0e20f;
const float kEdtInfinite = 1.0e19f;
// Largest finite half float: the distance stored when there is no background at all.
const float kHalfMax = 65504.0f;
// Largest Gaussian kernel radius, voxels.
const int kBlurMaxRadius = 32;

// The feature bakes' set 0 (bake/feature_bake.cpp): the source texture and
// the three r16f storage images the passes ping-pong between.
#define CW_FEATURE_BIND_SOURCE 0 // sampler3D: the values or the object mask
#define CW_FEATURE_BIND_SRC 1    // r16f storage image: a pass's input
#define CW_FEATURE_BIND_DST 2    // r16f storage image: a pass's output
#define CW_FEATURE_BIND_OUT 3    // r16f storage image: the finished field
// mask_blur.comp.glsl's window (voxels each side).
#define CW_FEATURE_SPEC_BLUR_WINDOW 0
// The region bake's set 0 (bake/feature_region.cpp).
#define CW_REGION_BIND_VALUES 0 // sampler3D: the values
#define CW_REGION_BIND_MASK 1   // sampler3D: M over the volume's grid
#define CW_REGION_BIND_OUT 2    // rg16f storage image: the region
// The field ranges' set 0 (bake/feature_ranges.cpp).
#define CW_RANGES_BIND_FIELD 0 // r16f storage image: the field
#define CW_RANGES_BIND_OUT 1   // rg8i storage image: each cell's range

// Push constants of every feature bake pass (64 bytes, std430 layout).
struct FeatureBakeParams {
    ivec3 dims;      // voxels
    int axis;        // edt_envelope, mask_blur: the axis of the lines (0 x, 1 y, 2 z)
    vec3 spacing;    // mm between voxel centres
    float threshold; // edt_lines: normalized value above which a voxel is object
    vec3 unused0;
    float sigma; // mask_blur: Gaussian sigma in voxels along `axis` (0: copy)
    int radius;  // mask_blur: kernel radius in voxels, <= kBlurMaxRadius
    int mode;    // field_finish: 0 distance, 1 mask; mask_blur: 1 reads the indicator
    int pad0;
    int pad1;
};

// Unnormalized Gaussian weight of the tap at offset i (voxels).
CW_FUNC float gaussianWeight(int i, float sigma) {
    if (sigma <= 0.0f) return i == 0 ? 1.0f : 0.0f;
    float t = float(i) / sigma;
    return exp(-0.5f * t * t);
}

// Intersection (abscissa) of the parabolas f(q) + w2 (p - q)^2 and
// f(r) + w2 (p - r)^2, r < q; w2 = spacing^2.
CW_FUNC float parabolaIntersection(float fq, int q, float fr, int r, float w2) {
    return ((fq - fr) / w2 + float(q * q - r * r)) / (2.0f * float(q - r));
}

// The distance in mm stored for a squared distance in mm^2 (kHalfMax when
// infinite or huge), and back (kEdtFar for kHalfMax).
CW_FUNC float storedDistance(float d2) {
    return min(sqrt(d2), kHalfMax);
}
CW_FUNC float squaredDistance(float stored) {
    return stored >= kHalfMax ? kEdtFar : stored * stored;
}

// M from the smoothed indicator s: >= 0.5 exactly at the segment's voxels, so
// nearest-voxel lookups agree with the segmentation and the trilinear field
// crosses 0.5 between inside and outside voxels.
CW_FUNC float maskEncode(float s, bool inside) {
    return inside ? max(s, 0.5f) : min(s, 0.498f);
}
// Whether a voxel whose stored M is `m` belongs to the segment.
CW_FUNC bool maskInside(float m) {
    return m >= 0.5f;
}

// Segment alignment's feature texture over one operator's region (the voxels
// its baked map can read, its deformed box, and a margin): RG16F, r = M as
// maskEncode stores it, g = the value moved material reads there (movedValue).
// Push constants of feature_region.comp.
struct FeatureRegionParams {
    ivec3 lo; // the region's first voxel in the volume's grid
    int pad0;
    ivec3 size; // the region's voxels along each axis
    int pad1;
    ivec3 dims; // the volume's grid
    int pad2;
};

// The value material that moves with the operator reads at a voxel (Eq. 4's
// p = p0, where M(p0) < 0.5). A voxel of the segment takes the mean of its
// neighbours outside the segment (26-connected: `outsideSum` over
// `outsideCount`); every other voxel, and one with no such neighbour, keeps
// its own. A point that moves has its nearest voxel outside the segment, so
// the eight voxels of its trilinear sample lie within one step of that voxel:
// none of them then carries the segment's value, and a scalp flap lifted off
// the skull takes no bone along with it (with the volume's own values its
// underside showed the skull's colour wherever the sample leaned on it).
CW_FUNC float movedValue(float own, bool inside, float outsideSum, float outsideCount) {
    return inside && outsideCount > 0.0f ? outsideSum / outsideCount : own;
}

// The range of a feature field over each cell of cellVoxels^3 voxels
// (feature_ranges.comp; bake/feature_ranges.hpp): the smallest and largest
// texel that a trilinear sample anywhere in the cell reads (the cell's voxels
// and one more on every side), in steps of 1 / scale rounded outward and
// clamped to a signed byte, so a range may be wider than the field's, never
// narrower (but where it is clamped: see fieldRangeHolds). Empty-space
// skipping for operators reads them (render/skipping/case_occupancy.hpp).
struct FieldRangeParams {
    ivec3 dims; // the field's voxels
    int cellVoxels;
    float scale; // steps per unit of the field
    int pad0;
    int pad1;
    int pad2;
};

CW_FUNC ivec2 encodeFieldRange(float lo, float hi, float scale) {
    return ivec2(int(clamp(floor(lo * scale), -128.0f, 127.0f)),
                 int(clamp(ceil(hi * scale), -128.0f, 127.0f)));
}

CW_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(cutaway::shader::FieldRangeParams) == 32);
static_assert(sizeof(cutaway::shader::FeatureBakeParams) == 64);
static_assert(offsetof(cutaway::shader::FeatureBakeParams, spacing) == 16);
static_assert(offsetof(cutaway::shader::FeatureBakeParams, unused0) == 32);
static_assert(offsetof(cutaway::shader::FeatureBakeParams, radius) == 48);
static_assert(sizeof(cutaway::shader::FeatureRegionParams) == 48);
#endif

#endif

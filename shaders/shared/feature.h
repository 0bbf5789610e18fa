// Feature-aligned manipulation (paper section 4), shared by the operator
// slicing shader and the C++ tests: which point a sample of the deformed space
// takes (Eq. 3, 4), the feature mask of surface alignment, and the normal
// blends of surface (Eq. 9) and segment alignment (Eq. 10).
//
// Gradients here follow the volume's convention (gradient.h): they point into
// the material, toward increasing value. The distance field DT grows into the
// object and the segment mask M grows into the segment, so their gradients
// point into the feature too.
#ifndef CUTAWAY_FEATURE_H
#define CUTAWAY_FEATURE_H

#include "shared/glsl_cpp.h"

#define CW_ALIGN_AXIS 0
#define CW_ALIGN_SURFACE 1
#define CW_ALIGN_SEGMENT 2

// The three cases of Eq. 4.
#define CW_CASE_TRANSFORMED 0 // p = p0: the point moved with the operator
#define CW_CASE_MASKED 1      // p = p': a feature point, left where it is
#define CW_CASE_EMPTY 2       // nothing: a cut, an opening, or the feature's place

CW_NAMESPACE_BEGIN

// Eq. 4. p0 is the probe of Eq. 3: T_B(p') inside the operator's box V_T, p'
// elsewhere (the baked map is the identity there). `p0Valid`: p0 exists (not
// in a cut) and lies in the volume; `pPrimeInVolume`: p' lies in the volume.
// Axis alignment is the case M = 0 everywhere, which gives Eq. 6.
CW_FUNC int featureCase(bool p0Valid, float maskAtP0, bool pPrimeInVolume, float maskAtPPrime) {
    if (p0Valid && maskAtPPrime < 0.5f && maskAtP0 < 0.5f) return CW_CASE_TRANSFORMED;
    if (pPrimeInVolume && maskAtPPrime >= 0.5f) return CW_CASE_MASKED;
    return CW_CASE_EMPTY;
}

// Surface alignment's mask from the distance field (mm below the surface):
// M >= 0.5 exactly where DT >= tau, rising linearly over tau +- delta.
CW_FUNC float surfaceMask(float dt, float tau, float delta) {
    if (delta <= 0.0f) return dt >= tau ? 1.0f : 0.0f;
    return clamp(0.5f + (dt - tau) / (2.0f * delta), 0.0f, 1.0f);
}

// Segment alignment's mask from the baked field: `smoothed` is the trilinear
// sample of the smoothed segment, `nearestInside` whether the nearest voxel
// belongs to the segment. A voxel of the segment always counts as feature, so
// a sample classified by the segment's label never moves with the operator.
// At p0, where material may leave, only where labels classify: elsewhere the
// mask there is `smoothed` alone, whose 0.5 surface is smooth where this rule
// draws the voxels' staircase, which the light showed as a lattice on a
// flap's underside.
CW_FUNC float segmentMask(float smoothed, bool nearestInside) {
    return max(smoothed, nearestInside ? 0.5f : 0.0f);
}

// beta of Eq. 9: 0 outside DT in (tau - delta, tau + delta); from 1 at DT = tau
// down to 0 at tau + delta on the feature's side; from 0 at tau - delta down
// to -1 at tau on the side that moves (its normal turns away from the feature).
CW_FUNC float surfaceBeta(float dt, float tau, float delta) {
    if (delta <= 0.0f) return 0.0f;
    if (dt > tau - delta && dt < tau) return (tau - dt) / delta - 1.0f;
    if (dt >= tau && dt < tau + delta) return (tau - dt) / delta + 1.0f;
    return 0.0f;
}

// Eq. 9: the transformed normal blended with the distance field's.
CW_FUNC vec3 surfaceNormal(vec3 transformed, vec3 distanceGradient, float beta) {
    return (1.0f - abs(beta)) * transformed + beta * distanceGradient;
}

// gamma of Eq. 10: 2M between the isosurfaces M = 0 and M = 0.5, else 0.
CW_FUNC float segmentGamma(float m) {
    return (m > 0.0f && m < 0.5f) ? 2.0f * m : 0.0f;
}

// Eq. 10: the transformed normal turned over as M approaches 0.5 from outside.
CW_FUNC vec3 segmentNormal(vec3 transformed, float gamma) {
    return (1.0f - 2.0f * gamma) * transformed;
}

// Section 4.3: for segmented data a neighbour counts 1 when it belongs to the
// segment of interest and 0 otherwise (another segment, or empty), so the
// gradient points into the segment on both sides of its boundary. The bake
// (feature_bake.h) takes these values smoothed by the segment's band, and the
// shader reads the gradient of that field; the unsmoothed difference below is
// the definition the tests check the property against.
CW_FUNC float segmentValue(bool inSegmentOfInterest) {
    return inSegmentOfInterest ? 1.0f : 0.0f;
}

// Central difference of segment values along one axis (mm spacing).
CW_FUNC float segmentDifference(bool below, bool above, float spacing) {
    return (segmentValue(above) - segmentValue(below)) / (2.0f * spacing);
}

// The unit gradient of a baked feature field (DT or M) at a point, from the
// field's values one voxel below and above it along each axis (the trilinear
// samples at tc -+ one voxel, clamped to the grid); `halfInvSpacing` is
// 1 / (2 spacing) in 1/mm. Toward increasing value, i.e. into the feature;
// zero where the field is flat. Only its direction is used (Eq. 9, 10).
CW_FUNC vec3 featureGradientOf(vec3 below, vec3 above, vec3 halfInvSpacing) {
    vec3 g = (above - below) * halfInvSpacing;
    float len = length(g);
    if (len < 1e-12f) return vec3(0.0f);
    return g / len;
}

CW_NAMESPACE_END

#endif

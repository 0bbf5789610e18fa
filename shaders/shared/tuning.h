// The renderer's tuning constants, one line of why each: numbers that set how
// fast a frame renders, not what it shows (the images are the same for any
// value that keeps the static_asserts below). Measured on lavapipe (2 cores)
// and an NVIDIA H200; docs/design/ has the measurements. GLSL and C++ alike.
#ifndef CUTAWAY_TUNING_H
#define CUTAWAY_TUNING_H

#include "shared/glsl_cpp.h"

CW_NAMESPACE_BEGIN

// Slices drawn between two saturation passes (early ray termination for
// slicing): fewer end sooner but pause more, each pause a full-screen pass
// (~0.3 ms at 512^2 on lavapipe).
const int kSlicesPerChunk = 16;
// Voxels along a side of a slicing brick (empty-space skipping): each
// occupied run of bricks is a proxy box, whose polygons cost per edge; 8
// keeps them few and still cuts most of the air.
const int kBrickVoxels = 8;
// Voxels along a side of a ray caster's cell: rays test a cell per sample,
// so finer cells skip more air at no cost in polygons.
const int kRayCellVoxels = 2;
// Map texels along a side of an operator's region block: about a brick.
const int kOperatorBlockTexels = 2;
// Rows of the ray caster's 8x8-pixel tiles per band (shared/tile_order.h): 2
// measured 3-6 % faster than single rows on ct_head and the frog on
// lavapipe, 4 about as fast, 8 slower. A GPU does not care.
const uint kTileBand = 2u;
// The most an upload stages at once, in MiB (at least one z-slice or layer):
// large enough to stream at full speed, small enough not to double a scan's
// memory on the host.
const int kStagingMiB = 16;

CW_NAMESPACE_END

#ifdef __cplusplus
namespace cutaway::shader {
// Regions covering more of an operator's box than this are not worth their
// stencil pass and extra polygon edges: the box is shaded whole (brain_t1's
// operator, 86 %, renders as fast either way on lavapipe). C++ only.
inline constexpr double kWholeBoxCoverage = 0.85;
} // namespace cutaway::shader

static_assert(cutaway::shader::kBrickVoxels % cutaway::shader::kRayCellVoxels == 0 &&
                  ((cutaway::shader::kBrickVoxels / cutaway::shader::kRayCellVoxels) &
                   (cutaway::shader::kBrickVoxels / cutaway::shader::kRayCellVoxels - 1)) == 0,
              "bricks take their spans from the cells, coarsened by powers of 2");
#endif

#endif

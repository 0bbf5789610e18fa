#pragma once
// Analytic smooth objects in millimetres, the ground truth of the
// reconstruction tests (reconstruction_test.cpp): an off-centre ellipsoid of
// value 200 in air (0) whose edge is a 1.5 mm smoothstep, and the same
// ellipsoid carrying bumps 1 mm high (out and in) and 8 mm in wavelength,
// detail that a blur would lose. Each is sampled at the voxel centres of a
// grid of `spacing` over one box of 40 x 40 x 42 mm, into uint8, so every
// grid holds the same object and renders in the same place.
#include "scene/scene.hpp"
#include "volume/volume.hpp"

namespace cutaway::test {

enum class SmoothObject { Ellipsoid, Bumpy };

inline constexpr glm::dvec3 kSmoothObjectBox{40.0, 40.0, 42.0};

/// The object on the grid of `spacing` (each a divisor of the box's sides).
Volume sampleSmoothObject(SmoothObject object, glm::dvec3 spacing);

/// An opaque, lit view of the objects: `size` pixels square over a
/// transparent background, from the side and above so that slices in z run
/// across the picture; a headlight and a light from the upper left, the
/// transfer functions' alpha per millimetre whatever the grid, and a
/// sample every 0.25 mm along each ray for every grid.
Scene smoothObjectScene(int size, RenderMethod method);

} // namespace cutaway::test

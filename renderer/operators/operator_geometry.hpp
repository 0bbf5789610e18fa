#pragma once
// Where operators are, computed on the CPU from the shared header: the local
// box their baked map must cover (V_T united with T_F(V_T), the deformed box
// V'_T of the paper), its place in the world, and whether two operators
// overlap (refused: they would be rendered twice).
#include "scene/scene.hpp"

#include <array>
#include <glm/glm.hpp>
#include <vector>

namespace cutaway::operators {

/// An axis-aligned box in some frame.
struct LocalBox {
    glm::dvec3 lo{-1.0};
    glm::dvec3 hi{1.0};
    bool operator==(const LocalBox&) const = default;
};

/// V_T united with the bounds of T_F over V_T (sampled densely on the box and
/// inside it): where the operator's material can be.
LocalBox materialBounds(const shader::OperatorParams& params);

/// materialBounds padded by one texel of `resolution`: the domain of the baked
/// map, whose edge texels then lie outside the moved material.
LocalBox deformedBounds(const shader::OperatorParams& params, glm::ivec3 resolution);

/// The parameters a map over `box` with `resolution` texels evaluates: a
/// peeler carves a gap of two texels (of its coarsest axis) where its flap
/// meets untouched material (b.y in shared/operators.h); others unchanged.
shader::OperatorParams sampledParams(const shader::OperatorParams& params, const LocalBox& box,
                                     glm::ivec3 resolution);

/// A bound on how fast the operator's signed cut distance w changes, in its
/// units per mm: w is a distance in the peeler's frame of equal units (one
/// unit its half z) and in the others' local frame (shared/operators.h).
double cutSlope(const OperatorSpec& op);

/// How far beyond a cut, in units of w, a sample may still show part of the
/// material when a cut's coverage is taken over a pixel's footprint
/// (/render/cut_antialias): the coarsest texel of the map over `domain`, as
/// wide as the gap a peeler carves between its flap and the material.
double cutMarginCap(const OperatorSpec& op, const LocalBox& domain);

/// An oriented box in the world: the local box under an affine map.
struct WorldBox {
    glm::dmat4 localToWorld{1.0};
    LocalBox local;
    std::array<glm::dvec3, 8> corners() const;
    glm::dvec3 lo() const; ///< world axis-aligned bounds
    glm::dvec3 hi() const;
};

/// The operator's deformed box in the world.
WorldBox worldBox(const OperatorSpec& op);

/// Whether two oriented boxes intersect (separating-axis test on 15 axes).
bool intersects(const WorldBox& a, const WorldBox& b);

/// Throws InputError naming both operators when two deformed boxes overlap.
void checkNoOverlap(const std::vector<OperatorSpec>& operators);
/// The same with the boxes already computed (boxes[i] is operators[i]'s).
void checkNoOverlap(const std::vector<OperatorSpec>& operators, const std::vector<WorldBox>& boxes);

} // namespace cutaway::operators

#include "operators/operator_geometry.hpp"

#include "core/error.hpp"
#include "shared/operators.h"

#include <algorithm>
#include <cmath>

namespace cutaway::operators {

LocalBox materialBounds(const shader::OperatorParams& params) {
    LocalBox box; // starts as V_T itself
    constexpr int n = 24;
    for (int k = 0; k <= n; ++k)
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) {
                const glm::vec3 p(-1.0f + 2.0f * float(i) / n, -1.0f + 2.0f * float(j) / n,
                                  -1.0f + 2.0f * float(k) / n);
                const glm::dvec3 q(shader::operatorForward(p, params));
                box.lo = glm::min(box.lo, q);
                box.hi = glm::max(box.hi, q);
            }
    return box;
}

LocalBox deformedBounds(const shader::OperatorParams& params, glm::ivec3 resolution) {
    LocalBox box = materialBounds(params);
    const glm::dvec3 texel = (box.hi - box.lo) / glm::dvec3(resolution);
    box.lo -= texel;
    box.hi += texel;
    return box;
}

namespace {

// The coarsest texel of a map with `resolution` texels over `box`, in units
// of w: the peeler's frame of equal units (x and y times X and Y), the
// others' local frame.
double coarsestTexel(const shader::OperatorParams& params, const LocalBox& box,
                     glm::ivec3 resolution) {
    glm::dvec3 texel = (box.hi - box.lo) / glm::dvec3(resolution);
    if (params.kind.x == CW_OP_PEELER) texel *= glm::dvec3(params.b.z, params.b.w, 1.0);
    return std::max({texel.x, texel.y, texel.z});
}

} // namespace

shader::OperatorParams sampledParams(const shader::OperatorParams& params, const LocalBox& box,
                                     glm::ivec3 resolution) {
    shader::OperatorParams p = params;
    if (p.kind.x == CW_OP_PEELER) p.b.y = static_cast<float>(coarsestTexel(p, box, resolution));
    return p;
}

double cutSlope(const OperatorSpec& op) {
    const glm::dmat3 a(op.localToWorld);
    if (op.type == OperatorType::Peeler) return 1.0 / glm::length(a[2]);
    return 1.0 / std::min({glm::length(a[0]), glm::length(a[1]), glm::length(a[2])});
}

double cutMarginCap(const OperatorSpec& op, const LocalBox& domain) {
    return coarsestTexel(op.params, domain, op.resolution); // the peeler's gap (sampledParams)
}

std::array<glm::dvec3, 8> WorldBox::corners() const {
    std::array<glm::dvec3, 8> c;
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 p((i & 1) ? local.hi.x : local.lo.x, (i & 2) ? local.hi.y : local.lo.y,
                           (i & 4) ? local.hi.z : local.lo.z);
        c[static_cast<std::size_t>(i)] = glm::dvec3(localToWorld * glm::dvec4(p, 1.0));
    }
    return c;
}

glm::dvec3 WorldBox::lo() const {
    glm::dvec3 m(1e300);
    for (const auto& c : corners())
        m = glm::min(m, c);
    return m;
}

glm::dvec3 WorldBox::hi() const {
    glm::dvec3 m(-1e300);
    for (const auto& c : corners())
        m = glm::max(m, c);
    return m;
}

WorldBox worldBox(const OperatorSpec& op) {
    return WorldBox{op.localToWorld, deformedBounds(op.params, op.resolution)};
}

bool intersects(const WorldBox& a, const WorldBox& b) {
    const auto ca = a.corners(), cb = b.corners();
    std::vector<glm::dvec3> axes;
    glm::dvec3 ea[3], eb[3];
    for (int i = 0; i < 3; ++i) {
        ea[i] = glm::dvec3(a.localToWorld[i]);
        eb[i] = glm::dvec3(b.localToWorld[i]);
    }
    // Face normals of an affine box are the rows of the inverse linear part.
    const glm::dmat3 na = glm::transpose(glm::inverse(glm::dmat3(a.localToWorld)));
    const glm::dmat3 nb = glm::transpose(glm::inverse(glm::dmat3(b.localToWorld)));
    for (int i = 0; i < 3; ++i) {
        axes.push_back(na[i]);
        axes.push_back(nb[i]);
        for (int j = 0; j < 3; ++j)
            axes.push_back(glm::cross(ea[i], eb[j]));
    }
    for (const glm::dvec3& axis : axes) {
        if (glm::dot(axis, axis) < 1e-18) continue; // parallel edges
        double minA = 1e300, maxA = -1e300, minB = 1e300, maxB = -1e300;
        for (const auto& c : ca)
            minA = std::min(minA, glm::dot(c, axis)), maxA = std::max(maxA, glm::dot(c, axis));
        for (const auto& c : cb)
            minB = std::min(minB, glm::dot(c, axis)), maxB = std::max(maxB, glm::dot(c, axis));
        if (maxA <= minB || maxB <= minA) return false; // touching faces do not overlap
    }
    return true;
}

void checkNoOverlap(const std::vector<OperatorSpec>& operators) {
    std::vector<WorldBox> boxes;
    for (const auto& op : operators)
        boxes.push_back(worldBox(op));
    checkNoOverlap(operators, boxes);
}

void checkNoOverlap(const std::vector<OperatorSpec>& operators,
                    const std::vector<WorldBox>& boxes) {
    for (std::size_t i = 0; i < boxes.size(); ++i)
        for (std::size_t j = i + 1; j < boxes.size(); ++j)
            if (intersects(boxes[i], boxes[j]))
                throw InputError("/operators/" + std::to_string(i) + " and /operators/" +
                                 std::to_string(j) + ": \"" + operators[i].name + "\" and \"" +
                                 operators[j].name +
                                 "\" overlap (their deformed boxes intersect); move them apart, or "
                                 "set render.operator_composition to \"sequential\"");
}

} // namespace cutaway::operators

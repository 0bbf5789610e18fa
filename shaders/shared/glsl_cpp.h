// Lets one header compile as GLSL (included by shaders) and as C++ (with GLM).
// Keep shared code to the common subset: pass by value, no inout/out
// parameters, float literals with an f suffix (GLSL accepts it; C++ needs it so
// glm's templates deduce float), and only built-ins GLM also has.
#ifndef CUTAWAY_GLSL_CPP_H
#define CUTAWAY_GLSL_CPP_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>

namespace cutaway::shader {
using glm::ivec2;
using glm::ivec3;
using glm::ivec4;
using glm::mat3;
using glm::mat4;
using glm::uvec2;
using glm::vec2;
using glm::vec3;
using glm::vec4;
using uint = std::uint32_t;
using glm::abs;
using glm::any;
using glm::atan; // atan(y, x) is GLSL's two-argument arc tangent (std::atan2)
using glm::ceil;
using glm::clamp;
using glm::cos;
using glm::cross;
using glm::dot;
using glm::floor;
using glm::fract;
using glm::inverse;
using glm::length;
using glm::lessThan;
using glm::max;
using glm::min;
using glm::mix;
using glm::normalize;
using glm::outerProduct;
using glm::pow;
using glm::sign;
using glm::sin;
using glm::smoothstep;
using glm::sqrt;
using glm::transpose;
} // namespace cutaway::shader
#define CW_NAMESPACE_BEGIN namespace cutaway::shader {
#define CW_NAMESPACE_END }
#define CW_FUNC inline
#else
#define CW_NAMESPACE_BEGIN
#define CW_NAMESPACE_END
#define CW_FUNC
#endif

#endif

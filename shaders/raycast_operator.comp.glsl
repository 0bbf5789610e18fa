#version 460
// The ray caster for scenes with one operator (glsl/ray_march.h): the
// shader with operators, without the loop that walks two or three boxes.
// flavours: storage lanes
#extension GL_GOOGLE_include_directive : require
#ifdef CW_YIELD_LANES
#extension GL_KHR_shader_subgroup_ballot : require
#endif
#define CW_RAY_OPERATORS
#define CW_RAY_ONE_OPERATOR
#include "glsl/ray_march.h"

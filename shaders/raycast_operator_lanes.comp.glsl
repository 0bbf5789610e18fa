#version 460
// The ray caster for scenes with one operator, its lanes yielding to shading
// (raycast_operators_lanes.comp.glsl without the loop over two or three boxes).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_ballot : require
#define CW_YIELD_LANES
#define CW_RAY_OPERATORS
#define CW_RAY_ONE_OPERATOR
#include "glsl/ray_march.h"

#version 460
// The ray caster for scenes with operators (glsl/ray_march.h), its lanes
// yielding to shading as raycast_lanes.comp.glsl's do.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_ballot : require
#define CW_YIELD_LANES
#define CW_RAY_OPERATORS
#include "glsl/ray_march.h"

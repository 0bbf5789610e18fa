#version 460
// The ray caster for scenes with operators (glsl/ray_march.h).
// flavours: storage lanes
#extension GL_GOOGLE_include_directive : require
#ifdef CW_YIELD_LANES
#extension GL_KHR_shader_subgroup_ballot : require
#endif
#define CW_RAY_OPERATORS
#include "glsl/ray_march.h"

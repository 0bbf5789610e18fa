#version 460
// The ray caster for scenes without operators (glsl/ray_march.h).
// flavours: storage lanes
#extension GL_GOOGLE_include_directive : require
#ifdef CW_YIELD_LANES
#extension GL_KHR_shader_subgroup_ballot : require
#endif
#include "glsl/ray_march.h"

#version 460
// The ray caster for scenes without operators (glsl/ray_march.h), whose lanes
// stepping over transparent samples stop for a pass of shading as soon as one
// lane of the subgroup waits (CW_YIELD_LANES): used where the device has
// subgroup ballots and runs a subgroup's lanes in lock-step on a CPU
// (lavapipe).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_ballot : require
#define CW_YIELD_LANES
#include "glsl/ray_march.h"

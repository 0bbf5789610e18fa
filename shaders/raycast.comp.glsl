#version 460
// The ray caster for scenes without operators (glsl/ray_march.h).
#extension GL_GOOGLE_include_directive : require
#include "glsl/ray_march.h"

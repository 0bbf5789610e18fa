#version 460
// The ray caster for scenes with operators (glsl/ray_march.h).
#extension GL_GOOGLE_include_directive : require
#define CW_RAY_OPERATORS
#include "glsl/ray_march.h"

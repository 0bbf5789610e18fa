#version 460
#extension GL_GOOGLE_include_directive : require
#include "glsl/slice_operator.h"

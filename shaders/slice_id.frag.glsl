#version 460
#extension GL_GOOGLE_include_directive : require
#define CW_WRITE_ID
#include "glsl/slice_background.h"

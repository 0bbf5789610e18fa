#version 460
// flavours: storage mattes
#extension GL_GOOGLE_include_directive : require
#define CW_WRITE_ID
#include "glsl/slice_operator.h"

#version 460
// flavours: storage
#extension GL_GOOGLE_include_directive : require
#include "glsl/slice_background.h"

#version 460
// An opaque mesh's colour, into the mesh target; the volume is composited over
// it afterwards (see render/mesh_pass.hpp).
#extension GL_GOOGLE_include_directive : require
#include "glsl/mesh_shade.h"

layout(location = 0) out vec4 outColor;

void main() {
    outColor = shadeMesh();
}

#version 460
// An opaque mesh's colour, into the mesh target, and its distance from the
// eye (the "Z" channel where a mesh is nearer than the volume); the volume is
// composited over it afterwards (see render/mesh_pass.hpp).
#extension GL_GOOGLE_include_directive : require
#include "glsl/mesh_shade.h"

layout(location = 0) out vec4 outColor;
layout(location = 1) out float outDistance;

void main() {
    outColor = shadeMesh();
    outDistance = viewDepth(u, worldPos);
}

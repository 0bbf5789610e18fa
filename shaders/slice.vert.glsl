#version 460
// Slice polygons arrive in world space (clipped on the CPU); pass the world
// position on so the fragment shader can map it into the volume.
#extension GL_GOOGLE_include_directive : require
#include "shared/bindings.h"
#include "shared/frame.h"

layout(location = 0) in vec3 inWorld;
layout(location = 0) out vec3 worldPos;
layout(std140, set = 0, binding = CW_BIND_FRAME) uniform Frame {
    FrameUniforms u;
};

void main() {
    worldPos = inWorld;
    gl_Position = u.worldToClip * vec4(inWorld, 1.0);
}

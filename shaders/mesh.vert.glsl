#version 460
// Opaque meshes drawn before the volume (tool models, operator glyphs): world
// position and normal for the lighting, the frame's camera for the position.
#extension GL_GOOGLE_include_directive : require
#include "shared/bindings.h"
#include "shared/frame.h"
#include "shared/mesh_draw.h"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inColor;
layout(location = 0) out vec3 worldPos;
layout(location = 1) out vec3 worldNormal;
layout(location = 2) out vec4 color;
layout(std140, set = 0, binding = CW_BIND_FRAME) uniform Frame {
    FrameUniforms u;
};
layout(push_constant) uniform Push {
    MeshDraw draw;
};

void main() {
    vec4 world = draw.modelToWorld * vec4(inPosition, 1.0);
    worldPos = world.xyz;
    worldNormal = mat3(draw.normal0.xyz, draw.normal1.xyz, draw.normal2.xyz) * inNormal;
    color = draw.color.w > 0.5 ? vec4(draw.color.rgb, 1.0) : inColor;
    gl_Position = u.worldToClip * world;
}

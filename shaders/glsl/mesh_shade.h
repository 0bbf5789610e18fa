// The colour of an opaque mesh fragment: the frame's lights on the
// interpolated normal (Blinn-Phong of shared/shading.h, always on: a tool is a
// surface even when the volume is drawn unshaded). Premultiplied, alpha 1.
// Only mesh.frag includes it; it is a header to keep the lighting beside shading.h.
#extension GL_GOOGLE_include_directive : require
#include "shared/bindings.h"
#include "shared/frame.h"
#include "shared/shading.h"

layout(location = 0) in vec3 worldPos;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec4 color;
layout(std140, set = 0, binding = CW_BIND_FRAME) uniform Frame {
    FrameUniforms u;
};

vec4 shadeMesh() {
    vec3 toEye = u.eye.w > 0.5 ? normalize(u.eye.xyz - worldPos) : -u.viewDir.xyz;
    vec3 n = dot(worldNormal, worldNormal) > 1e-12 ? normalize(worldNormal) : toEye;
    Lighting light = lightSurface(n, viewerOf(toEye, u), u);
    return vec4(color.rgb * light.diffuse + light.specular, 1.0);
}

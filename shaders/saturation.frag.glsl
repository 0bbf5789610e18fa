#version 460
// Early ray termination for slicing: where the front-to-back composite is
// already opaque, write depth 0 so that the slices behind fail the early depth
// test and are never shaded. Elsewhere nothing is written.
#extension GL_GOOGLE_include_directive : require
#include "shared/bindings.h"

layout(set = 0, binding = CW_BIND_SATURATION_COMPOSITE) uniform sampler2D composite;
// The opacity at which a pixel takes no more samples (FrameUniforms::termination).
layout(push_constant) uniform Saturation {
    float opaqueAlpha;
};

void main() {
    if (texelFetch(composite, ivec2(gl_FragCoord.xy), 0).a < opaqueAlpha) discard;
    gl_FragDepth = 0.0;
}

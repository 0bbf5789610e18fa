// Where along its ray each pixel takes its samples: on the slicing planes,
// shifted by a fraction of the spacing that is the pixel's own (with
// /render/jitter) and the pass's (with /render/samples). Both methods call
// this with the same pixel centre, so slicing and ray casting still take the
// same samples. Deterministic: the same pixel, seed and pass give the same
// offset, so reruns stay bit-identical.
#ifndef CUTAWAY_SAMPLING_H
#define CUTAWAY_SAMPLING_H

#include "shared/glsl_cpp.h"

CW_NAMESPACE_BEGIN

// Interleaved gradient noise (Jimenez, "Next generation post processing in
// Call of Duty: Advanced Warfare", SIGGRAPH 2014): a value in [0, 1) per
// pixel whose neighbours in any small window take well spread values, so
// the noise left is fine-grained and the eye averages it.
CW_FUNC float interleavedGradientNoise(vec2 pixel) {
    return fract(52.9829189f * fract(dot(pixel, vec2(0.06711056f, 0.00583715f))));
}

// The offset, in slice spacings along the view, of the samples of the pixel
// whose centre is `pixel`. `sampling` is FrameUniforms::sampling: x 1 with
// jitter, y the pass's offset (pass / passes), z the seed.
CW_FUNC float sampleOffset(vec2 pixel, vec4 sampling) {
    float own = sampling.x > 0.5f ? interleavedGradientNoise(pixel + sampling.z * 5.588238f) : 0.0f;
    return fract(own + sampling.y);
}

CW_NAMESPACE_END

#endif

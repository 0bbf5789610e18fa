#pragma once
// A frame's image on the host: read back from a pass's colour target, the
// operator ids decoded, the meshes and the background composited behind it.
#include "gpu/context.hpp"
#include "gpu/resources.hpp"
#include "io/image.hpp"

#include <glm/glm.hpp>

namespace cutaway::render {

/// A colour target's pixels (the device's colour format, half or float
/// RGBA) from its readback buffer.
Image readImage(const gpu::Context& ctx, const gpu::Buffer& readback, int width, int height);

/// The operator_id channel's value for a pixel whose first visible sample
/// came from the proxy with `code` (CW_ID_BACKGROUND in
/// shaders/glsl/sample_common.h): -2 nothing visible, -1 the untouched
/// volume, i operator i.
float operatorIdOf(float code, bool covered);

/// `meshes` (opaque) behind `image`: the volume in front of a mesh was
/// composited over nothing, and the mesh lies behind it.
void compositeMeshes(Image& image, const Image& meshes);

/// The background (straight RGBA) behind everything.
void compositeUnder(Image& image, glm::vec4 background);

} // namespace cutaway::render

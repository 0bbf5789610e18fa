#pragma once
// A frame's image on the host: read back from a pass's colour target, the
// operator ids decoded, the meshes and the background composited behind it.
#include "gpu/context.hpp"
#include "gpu/resources.hpp"
#include "io/image.hpp"
#include "scene/scene.hpp"

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>

namespace cutaway::render {

/// A colour target's pixels (the device's colour format, half or float
/// RGBA) from its readback buffer.
Image readImage(const gpu::Context& ctx, const gpu::Buffer& readback, int width, int height);

/// `count` floats from a readback of the colour format (half or float).
std::vector<float> readColorTexels(const gpu::Context& ctx, const gpu::Buffer& readback,
                                   std::size_t count);

/// A pass's AOV targets on the host, 4 floats per pixel: `ids` the id
/// target's (proxy code, distance, label code, 1 where a sample was visible,
/// shaders/glsl/slice_common.h), `mattes` the two matte targets' (null
/// without mattes).
struct AovTexels {
    const float* ids = nullptr;
    const float* mattes[2] = {nullptr, nullptr};
};

/// The channels `output` asks for into `image` (whose size they are read
/// at): its operator ids, the distances (infinity where nothing was
/// visible), the label codes (0 there; labelIdsOf makes them ids) and the
/// mattes.
void readAovs(const OutputSettings& output, const AovTexels& texels, Image& image);

/// The labels' ids from their codes: a code c > 0 is label `lowest` + c - 1,
/// 0 none (0, as an unlabelled voxel).
void labelIdsOf(std::vector<float>& codes, std::int64_t lowest);

/// The meshes' distances (`distance`, R32F texels) in `image`'s depth where
/// a mesh (alpha > 0 in `meshes`) is nearer than its first visible sample.
void meshDepthUnder(Image& image, const Image& meshes, const float* distance);

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

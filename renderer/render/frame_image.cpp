#include "render/frame_image.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/packing.hpp>
#include <limits>

namespace cutaway::render {

std::vector<float> readColorTexels(const gpu::Context& ctx, const gpu::Buffer& readback,
                                   std::size_t count) {
    std::vector<float> values(count);
    if (ctx.formats().color == VK_FORMAT_R32G32B32A32_SFLOAT) {
        std::memcpy(values.data(), readback.mapped, count * sizeof(float));
    } else {
        const auto* halves = static_cast<const uint16_t*>(readback.mapped);
        for (std::size_t i = 0; i < count; ++i)
            values[i] = glm::unpackHalf1x16(halves[i]);
    }
    return values;
}

Image readImage(const gpu::Context& ctx, const gpu::Buffer& readback, int width, int height) {
    Image image(width, height);
    image.rgba = readColorTexels(ctx, readback, image.rgba.size());
    return image;
}

void readAovs(const OutputSettings& output, const AovTexels& texels, Image& image) {
    const std::size_t pixels = image.rgba.size() / 4;
    const float* ids = texels.ids;
    const auto covered = [&](std::size_t p) { return ids[4 * p + 3] > 0.5f; };
    if (output.operatorId) {
        image.operatorIds.resize(pixels);
        for (std::size_t p = 0; p < pixels; ++p)
            image.operatorIds[p] = operatorIdOf(ids[4 * p], covered(p));
    }
    if (output.depth) {
        image.depth.resize(pixels);
        for (std::size_t p = 0; p < pixels; ++p)
            image.depth[p] = covered(p) ? ids[4 * p + 1] : std::numeric_limits<float>::infinity();
    }
    if (output.labelId) {
        image.labelIds.resize(pixels);
        for (std::size_t p = 0; p < pixels; ++p)
            image.labelIds[p] = covered(p) ? std::round(ids[4 * p + 2]) : 0.0f;
    }
    image.mattes.clear();
    for (std::size_t m = 0; m < output.mattes.size(); ++m) {
        ImageChannel& matte = image.mattes.emplace_back();
        matte.name = output.mattes[m].channel;
        matte.values.resize(pixels);
        const float* texel = texels.mattes[m / 3];
        for (std::size_t p = 0; p < pixels; ++p)
            matte.values[p] = texel[4 * p + m % 3];
    }
}

void labelIdsOf(std::vector<float>& codes, std::int64_t lowest) {
    for (float& c : codes)
        c = c > 0.5f ? static_cast<float>(lowest + static_cast<std::int64_t>(c) - 1) : 0.0f;
}

void meshDepthUnder(Image& image, const Image& meshes, const float* distance) {
    for (std::size_t p = 0; p < image.depth.size(); ++p)
        if (meshes.rgba[4 * p + 3] > 0.0f) image.depth[p] = std::min(image.depth[p], distance[p]);
}

float operatorIdOf(float code, bool covered) {
    return covered ? std::round(code) - 3.0f : -2.0f;
}

void compositeMeshes(Image& image, const Image& meshes) {
    for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
        const float t = 1.0f - image.rgba[i + 3];
        for (int c = 0; c < 4; ++c)
            image.rgba[i + c] += t * meshes.rgba[i + c];
    }
}

void compositeUnder(Image& image, glm::vec4 background) {
    const glm::vec4 premultiplied(glm::vec3(background) * background.w, background.w);
    for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
        const float t = 1.0f - image.rgba[i + 3];
        for (int c = 0; c < 4; ++c)
            image.rgba[i + c] += t * premultiplied[c];
    }
}

} // namespace cutaway::render

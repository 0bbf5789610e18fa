#include "render/frame_image.hpp"

#include <cmath>
#include <cstring>
#include <glm/gtc/packing.hpp>

namespace cutaway::render {

Image readImage(const gpu::Context& ctx, const gpu::Buffer& readback, int width, int height) {
    Image image(width, height);
    const std::size_t count = image.rgba.size();
    if (ctx.formats().color == VK_FORMAT_R32G32B32A32_SFLOAT) {
        std::memcpy(image.rgba.data(), readback.mapped, count * sizeof(float));
    } else {
        const auto* halves = static_cast<const uint16_t*>(readback.mapped);
        for (std::size_t i = 0; i < count; ++i)
            image.rgba[i] = glm::unpackHalf1x16(halves[i]);
    }
    return image;
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

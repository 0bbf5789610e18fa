#include "fuzz_entry.hpp"

#include "core/error.hpp"
#include "mesh/mesh.hpp"
#include "scene/animation.hpp"
#include "scene/json_reader.hpp"
#include "scene/scene.hpp"
#include "volume/volume.hpp"

#include <algorithm>
#include <span>
#include <string>
#include <string_view>

namespace cutaway::fuzz {

namespace {

/// Frames of a sequence checked: validate checks every one (up to a million),
/// which would make a single input take minutes.
constexpr int kSampledFrames = 8;

std::span<const std::byte> bytesOf(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const std::byte*>(data), size};
}

/// Runs `read`; cutaway's own errors are the expected outcome of most inputs.
template <typename F>
void expectingInputErrors(F&& read) {
    try {
        read();
    } catch (const InputError&) {
    } catch (const RuntimeError&) {
    }
}

} // namespace

void fuzzScene(const std::uint8_t* data, std::size_t size) {
    expectingInputErrors([&] {
        const std::string source = "fuzz.json";
        const std::string_view text(reinterpret_cast<const char*>(data), size);
        const Scene scene = parseScene(parseJsonText(text, source), CUTAWAY_FUZZ_SCENE_DIR, source);
        const Animation& a = scene.animation;
        if (a.tracks.empty()) return;
        // Every frame of a short sequence, else the last and a few evenly spaced.
        const int step = std::max(1, (a.lastFrame - a.firstFrame) / kSampledFrames);
        for (int frame = a.firstFrame; frame < a.lastFrame; frame += step)
            sceneAtFrame(scene, frame);
        sceneAtFrame(scene, a.lastFrame);
    });
}

void fuzzNrrd(const std::uint8_t* data, std::size_t size) {
    expectingInputErrors([&] { valueRange(readNrrdBytes(bytesOf(data, size), "fuzz.nrrd")); });
}

void fuzzNifti(const std::uint8_t* data, std::size_t size) {
    expectingInputErrors([&] { valueRange(readNiftiBytes(bytesOf(data, size), "fuzz.nii")); });
}

void fuzzMetaImage(const std::uint8_t* data, std::size_t size) {
    expectingInputErrors([&] { valueRange(readMetaImageBytes(bytesOf(data, size), "fuzz.mha")); });
}

void fuzzNhdr(const std::uint8_t* data, std::size_t size) {
    expectingInputErrors([&] {
        valueRange(readNrrdBytes(bytesOf(data, size), "fuzz.nhdr", CUTAWAY_FUZZ_NHDR_DIR));
    });
}

void fuzzGltf(const std::uint8_t* data, std::size_t size) {
    expectingInputErrors([&] {
        const std::string_view bytes(reinterpret_cast<const char*>(data), size);
        mesh::loadGltfBytes(bytes, "fuzz.gltf", std::filesystem::path(CUTAWAY_FUZZ_MESH_DIR));
    });
}

} // namespace cutaway::fuzz

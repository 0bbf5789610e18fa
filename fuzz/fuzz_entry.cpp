#include "fuzz_entry.hpp"

#include "core/error.hpp"
#include "mesh/mesh.hpp"
#include "scene/animation.hpp"
#include "scene/json_reader.hpp"
#include "scene/scene.hpp"
#include "volume/dicom.hpp"
#include "volume/volume.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <string_view>
#include <unistd.h>

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

/// A folder of this process's own under the temporary folder, removed at exit.
class OwnFolder {
public:
    OwnFolder()
        : m_path(std::filesystem::temp_directory_path() /
                 ("cutaway-fuzz-" + std::to_string(::getpid()))) {
        std::filesystem::create_directories(m_path);
    }
    ~OwnFolder() {
        std::error_code ec;
        std::filesystem::remove_all(m_path, ec);
    }
    OwnFolder(const OwnFolder&) = delete;
    OwnFolder& operator=(const OwnFolder&) = delete;
    const std::filesystem::path& path() const { return m_path; }

private:
    std::filesystem::path m_path;
};

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

void fuzzDicom(const std::uint8_t* data, std::size_t size) {
    static const OwnFolder folder;
    const std::filesystem::path file = folder.path() / "slice.dcm";
    std::ofstream(file, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    expectingInputErrors([&] { valueRange(readDicom(file)); });
}

} // namespace cutaway::fuzz

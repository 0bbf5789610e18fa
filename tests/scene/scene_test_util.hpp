#pragma once
// Helpers shared by the scene tests.
#include "core/error.hpp"
#include "scene/scene.hpp"

#include <atomic>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <system_error>
#include <unistd.h>
#include <vector>

namespace cutaway::test {

/// The smallest valid scene.
inline nlohmann::json minimalScene() {
    return nlohmann::json::parse(R"({"version": 1, "volume": {"phantom": "head"}})");
}

/// minimalScene() with an RFC 7386 merge patch applied (null removes a key).
inline nlohmann::json patched(const std::string& patchText) {
    nlohmann::json document = minimalScene();
    document.merge_patch(nlohmann::json::parse(patchText));
    return document;
}

/// The message of the InputError that parseScene throws, or "" if it parses.
inline std::string parseError(const nlohmann::json& document,
                              const std::filesystem::path& baseDir = "/nonexistent/scenes") {
    try {
        parseScene(document, baseDir, "scene.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

/// The message of the InputError that loadScene throws, or "" if it loads.
inline std::string loadError(const std::filesystem::path& file) {
    try {
        loadScene(file);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

inline std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> result;
    std::istringstream stream(text);
    for (std::string line; std::getline(stream, line);)
        result.push_back(line);
    return result;
}

/// A fresh folder under the system's temporary folder, removed at the end.
class TempDir {
public:
    TempDir() {
        static std::atomic<int> counter{0};
        m_path =
            std::filesystem::temp_directory_path() /
            ("cutaway_scene_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
        std::filesystem::create_directories(m_path);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(m_path, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const std::filesystem::path& path() const { return m_path; }

    std::filesystem::path write(const std::string& name, const std::string& text) const {
        const std::filesystem::path file = m_path / name;
        std::filesystem::create_directories(file.parent_path());
        std::ofstream(file, std::ios::binary) << text;
        return file;
    }

private:
    std::filesystem::path m_path;
};

} // namespace cutaway::test

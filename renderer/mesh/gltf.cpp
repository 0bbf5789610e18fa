// glTF 2.0 tool meshes, parsed by tinygltf (Debian's shared build): the
// default scene's triangle primitives, with node transforms applied.
#include "core/error.hpp"
#include "io/input_file.hpp"
#include "io/json_limits.hpp"
#include "mesh/gltf_detail.hpp"
#include "mesh/mesh.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <new>
#include <optional>
#include <sys/stat.h>
#include <tiny_gltf.h>

namespace cutaway::mesh {
namespace {

// Textures are ignored: accept every image without decoding it, so stb_image
// never parses the (untrusted) image bytes.
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int,
               const unsigned char*, int, void*) {
    return true;
}

// tinygltf's messages end in newlines and may hold several lines.
std::string oneLine(std::string s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back())))
        s.pop_back();
    for (std::size_t at = s.find('\n'); at != std::string::npos; at = s.find('\n', at))
        s.replace(at, 1, "; ");
    return s;
}

// The largest model file (and file it names) read: tinygltf takes sizes as
// 32-bit numbers, and a tool model is a few megabytes.
constexpr std::uint64_t kMaxModelBytes = std::uint64_t{1} << 30;

// What tinygltf reads besides the model file, through cutaway's input checks
// (io/input_file.hpp): its own file access would block for ever in open() on
// a named pipe and read a folder as a file of absurd size. Without a folder
// (a model in memory) it reads nothing.
struct NamedFiles {
    std::optional<std::filesystem::path> folder;
    std::string model; ///< the model, for messages
    std::vector<std::filesystem::path> read;
    std::string error; ///< why the last read failed
};

bool namedFileExists(const std::string& path, void* user) {
    struct stat status {}; // any kind: readNamedFile says what is wrong with it
    return static_cast<NamedFiles*>(user)->folder && ::stat(path.c_str(), &status) == 0;
}

std::string keepFilePath(const std::string& path, void*) {
    return path;
}

bool readNamedFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                   void* user) {
    NamedFiles& files = *static_cast<NamedFiles*>(user);
    try {
        InputFile file(path, "a file the model names", files.model + ": " + path);
        const std::string bytes = file.readAll(kMaxModelBytes);
        out->assign(bytes.begin(), bytes.end());
        files.read.emplace_back(path);
        return true;
    } catch (const InputError& e) {
        files.error = e.what();
        if (err) *err += files.error;
        return false;
    }
}

bool writeNoFile(std::string*, const std::string&, const std::vector<unsigned char>&, void*) {
    return false;
}

// tinygltf reports a cut-off .glb only as "Invalid glTF binary."; say what is
// wrong. Returns the JSON chunk's text.
std::string_view glbJson(std::string_view bytes, const std::string& ctx) {
    if (bytes.size() < 12 || bytes.substr(0, 4) != "glTF")
        throw InputError(ctx + ": not a binary glTF file (no \"glTF\" magic at its start)");
    std::uint32_t version = 0, length = 0, jsonLength = 0;
    std::memcpy(&version, bytes.data() + 4, 4);
    std::memcpy(&length, bytes.data() + 8, 4);
    if (version != 2)
        throw InputError(ctx + ": unsupported binary glTF version " + std::to_string(version));
    if (length > bytes.size()) {
        throw InputError(ctx + ": truncated: the header gives " + std::to_string(length) +
                         " bytes, the file has " + std::to_string(bytes.size()));
    }
    if (bytes.size() < 20) return {}; // tinygltf says what is missing
    std::memcpy(&jsonLength, bytes.data() + 12, 4);
    return bytes.substr(20, jsonLength);
}

// Parses a model's bytes (.glb when `binary`), reading the files it names
// from `files.folder`.
tinygltf::Model parse(std::string_view bytes, bool binary, const std::string& ctx,
                      NamedFiles& files) {
    // The JSON is nested no deeper than a scene's before tinygltf, which
    // recurses once per level, reads it.
    checkJsonText(binary ? glbJson(bytes, ctx) : bytes, ctx, JsonLimits{});
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(&skipImage, nullptr);
    loader.SetFsCallbacks({&namedFileExists, &keepFilePath, &readNamedFile, &writeNoFile, &files});
    tinygltf::Model model;
    std::string err, warn;
    bool ok = false;
    const std::string folder = files.folder ? files.folder->string() : std::string();
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    const auto size = static_cast<unsigned int>(bytes.size());
    try {
        ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, data, size, folder)
                    : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), size, folder);
    } catch (const std::bad_alloc&) {
        throw;
    } catch (const std::exception& e) {
        // tinygltf reports through err; this is for anything that escapes it.
        throw InputError(ctx + ": not a valid glTF file: " + e.what());
    }
    if (!ok && !files.error.empty()) throw InputError(files.error);
    if (!ok) {
        std::string message = ctx + ": not a valid glTF file: " + oneLine(err);
        if (!warn.empty()) message += " (warnings: " + oneLine(warn) + ")";
        throw InputError(message);
    }
    return model;
}

bool isBinaryName(const std::filesystem::path& file, const std::string& ctx) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext != ".gltf" && ext != ".glb")
        throw InputError(ctx + ": unknown extension \"" + ext + "\" (expected .gltf or .glb)");
    return ext == ".glb";
}

// Reads the model file and parses it; `files` receives what it names.
tinygltf::Model parseFile(const std::filesystem::path& file, NamedFiles& files) {
    const std::string ctx = file.string();
    const bool binary = isBinaryName(file, ctx);
    const std::string bytes = InputFile(file, "glTF model").readAll(kMaxModelBytes);
    files.folder = file.parent_path().empty() ? std::filesystem::path(".") : file.parent_path();
    files.model = ctx;
    files.read.push_back(file);
    return parse(bytes, binary, ctx, files);
}

// The node's local transform: its matrix, or T * R * S.
glm::mat4 localTransform(const tinygltf::Node& node, int index, const std::string& ctx) {
    const auto need = [&](const std::vector<double>& v, std::size_t n, const char* field) {
        if (!v.empty() && v.size() != n) {
            throw InputError(ctx + ": node " + std::to_string(index) + ": " + field + " has " +
                             std::to_string(v.size()) + " numbers, expected " + std::to_string(n));
        }
    };
    need(node.matrix, 16, "matrix");
    need(node.translation, 3, "translation");
    need(node.rotation, 4, "rotation");
    need(node.scale, 3, "scale");
    glm::mat4 m(1.0f);
    if (!node.matrix.empty()) {
        for (int i = 0; i < 16; ++i) // column-major, like glm
            m[i / 4][i % 4] = static_cast<float>(node.matrix[i]);
        return m;
    }
    const auto vec = [](const std::vector<double>& v, glm::vec4 fallback) {
        for (std::size_t i = 0; i < v.size(); ++i)
            fallback[static_cast<int>(i)] = static_cast<float>(v[i]);
        return fallback;
    };
    const glm::vec3 t(vec(node.translation, glm::vec4(0.0f)));
    const glm::vec3 s(vec(node.scale, glm::vec4(1.0f)));
    glm::vec4 q = vec(node.rotation, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)); // x, y, z, w
    // Exporters round quaternions; renormalize so R stays a rotation.
    const float len = glm::length(q);
    q = len > 0.0f ? q / len : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    const float x = q.x, y = q.y, z = q.z, w = q.w;
    const glm::vec3 rx(1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y));
    const glm::vec3 ry(2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x));
    const glm::vec3 rz(2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y));
    m[0] = glm::vec4(rx * s.x, 0.0f);
    m[1] = glm::vec4(ry * s.y, 0.0f);
    m[2] = glm::vec4(rz * s.z, 0.0f);
    m[3] = glm::vec4(t, 1.0f);
    return m;
}

// glTF's default scene, else scene 0, else every node that is nobody's child.
std::vector<int> sceneRoots(const tinygltf::Model& model, const std::string& ctx) {
    if (model.defaultScene >= 0) {
        if (static_cast<std::size_t>(model.defaultScene) >= model.scenes.size())
            throw InputError(ctx + ": scene " + std::to_string(model.defaultScene) +
                             " does not exist");
        return model.scenes[model.defaultScene].nodes;
    }
    if (!model.scenes.empty()) return model.scenes[0].nodes;
    std::vector<bool> isChild(model.nodes.size(), false);
    for (const tinygltf::Node& node : model.nodes) {
        for (int c : node.children) {
            if (c >= 0 && static_cast<std::size_t>(c) < isChild.size()) isChild[c] = true;
        }
    }
    std::vector<int> roots;
    for (std::size_t i = 0; i < isChild.size(); ++i) {
        if (!isChild[i]) roots.push_back(static_cast<int>(i));
    }
    return roots;
}

// The triangles of a parsed model's default scene, in world units.
TriangleMesh trianglesOf(const tinygltf::Model& model, const std::string& ctx) {
    // Depth-first in document order, with an explicit stack: a hostile file
    // may nest nodes deeper than the call stack would allow.
    struct Pending {
        int node;
        glm::mat4 parentToWorld;
    };
    std::vector<Pending> stack;
    const std::vector<int> roots = sceneRoots(model, ctx);
    for (auto it = roots.rbegin(); it != roots.rend(); ++it)
        stack.push_back({*it, glm::mat4(1.0f)});
    std::vector<bool> visited(model.nodes.size(), false);
    TriangleMesh result;
    while (!stack.empty()) {
        const Pending item = stack.back();
        stack.pop_back();
        const std::string name = "node " + std::to_string(item.node);
        if (item.node < 0 || static_cast<std::size_t>(item.node) >= model.nodes.size())
            throw InputError(ctx + ": " + name + " does not exist");
        // Node hierarchies are trees; a second visit means a cycle or a shared child.
        if (visited[item.node])
            throw InputError(ctx + ": " + name + " is reached twice (a cycle in the node tree?)");
        visited[item.node] = true;
        const tinygltf::Node& node = model.nodes[item.node];
        const glm::mat4 toWorld = item.parentToWorld * localTransform(node, item.node, ctx);
        if (node.mesh != -1) {
            if (node.mesh < 0 || static_cast<std::size_t>(node.mesh) >= model.meshes.size()) {
                throw InputError(ctx + ": " + name + " refers to mesh " +
                                 std::to_string(node.mesh) + ", which does not exist");
            }
            const std::size_t count = model.meshes[node.mesh].primitives.size();
            for (std::size_t p = 0; p < count; ++p)
                detail::addPrimitive(result, model, node.mesh, static_cast<int>(p), toWorld, ctx);
        }
        for (auto it = node.children.rbegin(); it != node.children.rend(); ++it)
            stack.push_back({*it, toWorld});
    }
    if (result.indices.empty()) throw InputError(ctx + ": no triangle meshes");
    return result;
}

} // namespace

TriangleMesh loadGltf(const std::filesystem::path& file) {
    NamedFiles files;
    return trianglesOf(parseFile(file, files), file.string());
}

TriangleMesh loadGltfBytes(std::string_view bytes, const std::string& name,
                           const std::optional<std::filesystem::path>& folder) {
    NamedFiles files;
    files.model = name;
    files.folder = folder;
    return trianglesOf(parse(bytes, bytes.substr(0, 4) == "glTF", name, files), name);
}

std::vector<std::filesystem::path> gltfFiles(const std::filesystem::path& file) {
    NamedFiles files;
    parseFile(file, files);
    return files.read;
}

} // namespace cutaway::mesh

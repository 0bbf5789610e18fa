// What a glTF model reads: its JSON (nested no deeper than a scene's) and
// the files its buffers name (regular files only, never blocking), and the
// same model read from memory.
#include "core/error.hpp"
#include "gltf_writer.hpp"
#include "io/named_pipe.hpp"

#include <fstream>
#include <iterator>

namespace cutaway::test {
namespace {

using mesh::loadGltf;

// One triangle; buffer 0 is `uri` (a file next to the model) or a data URI.
struct Triangle {
    Bin bin;
    std::size_t pos = bin.add(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
    std::size_t idx = bin.add(std::vector<std::uint16_t>{0, 1, 2, 0});

    std::string body(const std::string& extras = "null") const {
        return R"("scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}], "meshes": [{"primitives":
            [{"attributes": {"POSITION": 0}, "indices": 1}]}], "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
            {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
            "bufferViews": [{"buffer": 0, "byteOffset": )" +
               std::to_string(pos) + R"(, "byteLength": 36}, {"buffer": 0, "byteOffset": )" +
               std::to_string(idx) + R"(, "byteLength": 6}], "extras": )" + extras;
    }
    // A .gltf whose buffer is the file `uri`.
    std::string withBufferFile(const std::string& uri) const {
        return R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": )" +
               std::to_string(bin.bytes.size()) + R"(, "uri": ")" + uri + "\"}], " + body() + "}";
    }
};

std::string errorOf(const std::filesystem::path& file) {
    try {
        (void)loadGltf(file);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

std::string nestedArrays(int depth) {
    return std::string(static_cast<std::size_t>(depth), '[') +
           std::string(static_cast<std::size_t>(depth), ']');
}

TEST(GltfFiles, JsonNestedDeeperThanAScenesIsRefusedBeforeParsing) {
    TempDir dir;
    const Triangle t;
    // 20,000 levels overflowed the stack of tinygltf's recursive parser.
    writeGltf(dir / "deep.gltf", t.body(nestedArrays(20000)), t.bin);
    writeGlb(dir / "deep.glb", t.body(nestedArrays(20000)), t.bin);
    for (const char* name : {"deep.gltf", "deep.glb"}) {
        const std::string message = errorOf(dir / name);
        EXPECT_EQ(message.rfind((dir / name).string() + ":", 0), 0u) << message;
        EXPECT_NE(message.find(": nesting deeper than 64 levels"), std::string::npos) << message;
    }
    // The control: extras 64 levels deep are read.
    writeGltf(dir / "ok.gltf", t.body(nestedArrays(63)), t.bin);
    writeGlb(dir / "ok.glb", t.body(nestedArrays(63)), t.bin);
    EXPECT_EQ(loadGltf(dir / "ok.gltf").triangleCount(), 1u);
    EXPECT_EQ(loadGltf(dir / "ok.glb").triangleCount(), 1u);
}

TEST(GltfFiles, ABufferThatIsNoRegularFileIsBadInputSayingWhatItIs) {
    TempDir dir;
    const Triangle t;
    std::filesystem::create_directories(dir / "folder");
    const NamedPipe pipe(dir / "pipe.bin");
    ASSERT_TRUE(pipe.made());
    writeText(dir / "folder.gltf", t.withBufferFile("folder"));
    writeText(dir / "pipe.gltf", t.withBufferFile("pipe.bin"));
    // A folder gave std::bad_alloc; a pipe blocked in open() for ever.
    EXPECT_EQ(errorOf(dir / "folder.gltf"),
              (dir / "folder.gltf").string() + ": " + (dir / "folder").string() +
                  ": cannot read a file the model names (it is a folder, not a regular file)");
    EXPECT_EQ(errorOf(dir / "pipe.gltf"),
              (dir / "pipe.gltf").string() + ": " + (dir / "pipe.bin").string() +
                  ": cannot read a file the model names (it is a named pipe (FIFO), not a "
                  "regular file)");
    EXPECT_FALSE(pipe.wasOpened());
    // The control: the same model with its buffer in a regular file.
    writeBytes(dir / "tri.bin", t.bin.bytes);
    writeText(dir / "tri.gltf", t.withBufferFile("tri.bin"));
    EXPECT_EQ(loadGltf(dir / "tri.gltf").triangleCount(), 1u);
    EXPECT_EQ(mesh::gltfFiles(dir / "tri.gltf"),
              (std::vector<std::filesystem::path>{dir / "tri.gltf", dir / "tri.bin"}));
}

TEST(GltfFiles, AModelInMemoryReadsAsItsFileAndNamesNoFiles) {
    const std::filesystem::path meshes =
        std::filesystem::path(CUTAWAY_SOURCE_DIR) / "scenes/meshes";
    for (const char* name : {"forceps.gltf", "retractor.glb"}) {
        std::ifstream in(meshes / name, std::ios::binary);
        const std::string bytes{std::istreambuf_iterator<char>(in), {}};
        const mesh::TriangleMesh fromFile = loadGltf(meshes / name);
        const mesh::TriangleMesh fromMemory = mesh::loadGltfBytes(bytes, name);
        EXPECT_GT(fromFile.triangleCount(), 0u) << name;
        EXPECT_EQ(fromMemory.indices, fromFile.indices) << name;
        EXPECT_EQ(fromMemory.positions, fromFile.positions) << name;
    }
    TempDir dir;
    const Triangle t;
    writeBytes(dir / "tri.bin", t.bin.bytes);
    EXPECT_THROW(mesh::loadGltfBytes(t.withBufferFile((dir / "tri.bin").string()), "tri.gltf"),
                 InputError);
}

} // namespace
} // namespace cutaway::test

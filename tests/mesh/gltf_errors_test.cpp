// loadGltf on broken and hostile files: each is an InputError that names the
// file and what is wrong, never a crash.
#include "core/error.hpp"
#include "gltf_writer.hpp"

#include <limits>

namespace cutaway::test {
namespace {

using mesh::loadGltf;

// A valid one-triangle model; `accessors` and `primitive` may be replaced.
struct Model {
    Bin bin;
    std::size_t pos = bin.add(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
    std::size_t idx = bin.add(std::vector<std::uint16_t>{0, 1, 2, 0});
    std::string primitive = R"({"attributes": {"POSITION": 0}, "indices": 1})";
    std::string accessors = R"({"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
        {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"})";
    std::string nodes = R"({"mesh": 0})";

    std::string body() const {
        return R"("scenes": [{"nodes": [0]}], "nodes": [)" + nodes +
               R"(], "meshes": [{"primitives": [)" + primitive + R"(]}], "accessors": [)" +
               accessors + R"(], "bufferViews": [{"buffer": 0, "byteOffset": )" +
               std::to_string(pos) + R"(, "byteLength": 36}, {"buffer": 0, "byteOffset": )" +
               std::to_string(idx) + R"(, "byteLength": 6}])";
    }
};

// loadGltf(file) throws an InputError naming the file and containing `phrase`.
void expectError(const std::filesystem::path& file, const std::string& phrase) {
    try {
        (void)loadGltf(file);
        ADD_FAILURE() << file << ": no error, expected \"" << phrase << "\"";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(file.string()), std::string::npos) << message;
        EXPECT_NE(message.find(phrase), std::string::npos) << message;
    }
}

TEST(GltfErrors, ValidModelLoads) {
    TempDir dir;
    Model model;
    writeGlb(dir / "ok.glb", model.body(), model.bin);
    EXPECT_EQ(loadGltf(dir / "ok.glb").triangleCount(), 1u);
}

TEST(GltfErrors, TruncatedGlb) {
    TempDir dir;
    Model model;
    std::vector<unsigned char> bytes = glbBytes(model.body(), model.bin);
    bytes.resize(bytes.size() - 20);
    writeBytes(dir / "cut.glb", bytes);
    expectError(dir / "cut.glb", "truncated");
    bytes.resize(7);
    writeBytes(dir / "stub.glb", bytes);
    expectError(dir / "stub.glb", "not a binary glTF file");
}

TEST(GltfErrors, JsonSyntaxErrorCarriesTinygltfMessage) {
    TempDir dir;
    writeText(dir / "syntax.gltf", R"({"asset": {"version": "2.0"}, "nodes": [{"mesh": 0,]})");
    expectError(dir / "syntax.gltf", "not a valid glTF file: ");
    expectError(dir / "syntax.gltf", "syntax error"); // nlohmann::json's words, via tinygltf
}

TEST(GltfErrors, AccessorPastTheEndOfItsBuffer) {
    TempDir dir;
    Model model;
    const std::string indices =
        R"(, {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"})";
    model.accessors = R"({"bufferView": 0, "byteOffset": 4, "componentType": 5126, "count": 9,
        "type": "VEC3"})" +
                      indices;
    writeGltf(dir / "long.gltf", model.body(), model.bin);
    expectError(dir / "long.gltf", "mesh 0 primitive 0: POSITION accessor 0 reads past the end of "
                                   "buffer 0");
    // Within the buffer but past the bufferView: POSITION reading the indices.
    model.accessors = R"({"bufferView": 0, "byteOffset": 4, "componentType": 5126, "count": 3,
        "type": "VEC3"})" +
                      indices;
    writeGltf(dir / "view.gltf", model.body(), model.bin);
    expectError(dir / "view.gltf", "reads past the end of bufferView 0");
    // A count whose byte size overflows 64 bits.
    model.accessors = R"({"bufferView": 0, "componentType": 5126, "count": 1537228672809129302,
        "type": "VEC3"})" +
                      indices;
    writeGltf(dir / "huge.gltf", model.body(), model.bin);
    expectError(dir / "huge.gltf", "reads past the end of buffer 0");
}

TEST(GltfErrors, IndexOutOfRange) {
    TempDir dir;
    Model model;
    model.idx = model.bin.add(std::vector<std::uint16_t>{0, 1, 3, 0});
    writeGlb(dir / "index.glb", model.body(), model.bin);
    expectError(dir / "index.glb", "index 3 (element 2) is out of range: POSITION has 3 vertices");
}

TEST(GltfErrors, MissingFileAndUnknownExtension) {
    TempDir dir;
    expectError(dir / "absent.glb", "absent.glb: cannot read glTF model (no such file)");
    writeText(dir / "tool.obj", "v 0 0 0\n");
    expectError(dir / "tool.obj", "unknown extension \".obj\"");
}

TEST(GltfErrors, OnlyPointsIsNoTriangleMesh) {
    TempDir dir;
    Model model;
    model.primitive = R"({"attributes": {"POSITION": 0}, "mode": 0})";
    writeGltf(dir / "points.gltf", model.body(), model.bin);
    expectError(dir / "points.gltf", "no triangle meshes");
}

TEST(GltfErrors, SparseAccessor) {
    TempDir dir;
    Model model;
    model.accessors = R"({"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
        "sparse": {"count": 1, "indices": {"bufferView": 1, "componentType": 5123},
                   "values": {"bufferView": 0}}},
        {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"})";
    writeGltf(dir / "sparse.gltf", model.body(), model.bin);
    expectError(dir / "sparse.gltf", "POSITION accessor 0: sparse accessors are not supported");
}

TEST(GltfErrors, NonFinitePosition) {
    TempDir dir;
    Model model;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    model.pos = model.bin.add(std::vector<float>{0, 0, 0, 1, nan, 0, 0, 1, 0});
    writeGlb(dir / "nan.glb", model.body(), model.bin);
    expectError(dir / "nan.glb", "POSITION accessor 0 has a non-finite value in element 1");
}

TEST(GltfErrors, BadReferences) {
    TempDir dir;
    Model model;
    model.primitive = R"({"attributes": {"POSITION": 7}})";
    writeGltf(dir / "accessor.gltf", model.body(), model.bin);
    expectError(dir / "accessor.gltf", "POSITION: accessor 7 does not exist");

    model = Model();
    model.nodes = R"({"mesh": 4})";
    writeGltf(dir / "mesh.gltf", model.body(), model.bin);
    expectError(dir / "mesh.gltf", "node 0 refers to mesh 4, which does not exist");

    model = Model();
    model.nodes = R"({"mesh": 0, "children": [0]})";
    writeGltf(dir / "cycle.gltf", model.body(), model.bin);
    expectError(dir / "cycle.gltf", "node 0 is reached twice");

    model = Model();
    model.accessors = R"({"bufferView": 0, "componentType": 5123, "count": 3, "type": "VEC3"},
        {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"})";
    writeGltf(dir / "type.gltf", model.body(), model.bin);
    expectError(dir / "type.gltf",
                "POSITION accessor 0 must be FLOAT VEC3, not UNSIGNED_SHORT VEC3");
}

// Random byte changes to a valid .glb (JSON and binary chunk) and cuts at
// every length: each load either works or is an InputError.
TEST(GltfErrors, MutatedFilesNeverCrash) {
    TempDir dir;
    Model model;
    const std::vector<unsigned char> good = glbBytes(model.body(), model.bin);
    std::mt19937 random(12345);
    int failures = 0;
    for (int round = 0; round < 3000; ++round) {
        std::vector<unsigned char> bytes = good;
        if (round < static_cast<int>(good.size())) {
            bytes.resize(static_cast<std::size_t>(round));
        } else {
            const int changes = 1 + static_cast<int>(random() % 4);
            for (int c = 0; c < changes; ++c) {
                // Past the 12-byte header, mostly digits, so the JSON often
                // stays valid with other numbers in it.
                const std::size_t at = 12 + random() % (bytes.size() - 12);
                bytes[at] = random() % 3 ? static_cast<unsigned char>('0' + random() % 10)
                                         : static_cast<unsigned char>(random());
            }
        }
        writeBytes(dir / "m.glb", bytes);
        try {
            (void)loadGltf(dir / "m.glb");
        } catch (const InputError&) {
            ++failures;
        }
    }
    EXPECT_GT(failures, 500);
}

} // namespace
} // namespace cutaway::test

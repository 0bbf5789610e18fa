// Output paths through the binary: an output that is a file the run reads is
// refused before anything renders, however it is spelled; export's two
// outputs are compared as files; control characters, a trailing slash, a
// link loop and a path past PATH_MAX are refused by validate and render
// alike, with the same message.
#include "cli_util.hpp"

#include <climits>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

namespace fs = std::filesystem;

namespace cutaway::test {
namespace {

std::string contentOf(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

} // namespace

// A scene that reads six files: itself, a detached NRRD header and its data,
// a label volume, and a glTF model with its buffer in a file of its own.
class ReadFiles : public CliTest {
protected:
    void SetUp() override {
        CliTest::SetUp();
        std::string voxels(512, '\0'), labels(512, '\0');
        for (std::size_t i = 0; i < voxels.size(); ++i) {
            voxels[i] = static_cast<char>(i % 200);
            labels[i] = static_cast<char>(i % 2);
        }
        const std::string header = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 8 8 8\n"
                                   "encoding: raw\n";
        write("vol.nhdr", header + "data file: vol.raw\n");
        write("vol.raw", voxels);
        write("labels.nrrd", header + "\n" + labels);
        std::string bin;
        for (const float v : {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f})
            bin.append(reinterpret_cast<const char*>(&v), sizeof v);
        for (const std::uint16_t i : std::vector<std::uint16_t>{0, 1, 2, 0})
            bin.append(reinterpret_cast<const char*>(&i), sizeof i);
        write("tool.bin", bin);
        write("tool.gltf", R"({"asset": {"version": "2.0"},
            "buffers": [{"byteLength": 44, "uri": "tool.bin"}],
            "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36,
                             "byteLength": 6}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                          {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
            "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]})");
        m_scene = write("scene.json", R"({"version": 1, "volume": {"file": "vol.nhdr"},
            "labels": {"file": "labels.nrrd"},
            "meshes": [{"file": "tool.gltf", "placement": {"units": "mm", "scale": 4}}],
            "render": {"size": [16, 16]}, "output": {"pattern": "out/f_####.exr"}})");
        for (const char* name : kInputs)
            m_contents[name] = contentOf(m_dir / name);
    }

    void expectInputsIntact() {
        for (const char* name : kInputs)
            EXPECT_EQ(contentOf(m_dir / name), m_contents[name]) << name << " was overwritten";
        EXPECT_FALSE(fs::exists(m_dir / "out")) << "something was rendered";
    }

    static constexpr const char* kInputs[] = {"scene.json",  "vol.nhdr",  "vol.raw",
                                              "labels.nrrd", "tool.gltf", "tool.bin"};
    fs::path m_scene;
    std::map<std::string, std::string> m_contents;
};

TEST_F(ReadFiles, AnOutputThatIsAFileTheRunReadsIsRefusedBeforeAnythingRenders) {
    fs::create_directories(m_dir / "sub");
    fs::create_directory_symlink(m_dir, m_dir / "here");
    for (const char* name : kInputs) {
        // The plain name, another spelling, a link's: one file each time.
        fs::create_symlink(m_dir / name, m_dir / ("alias_" + std::string(name)));
        for (const fs::path& output :
             {m_dir / name, m_dir / "sub" / ".." / name, m_dir / "here" / name,
              m_dir / ("alias_" + std::string(name))}) {
            SCOPED_TRACE(output.string());
            for (const char* command : {"render", "validate"}) {
                CommandResult r = runCutaway(std::string(command) + " " + m_scene.string() +
                                             " --frames 0 -o " + output.string());
                EXPECT_EQ(r.code, 2) << command << ": " << r.output;
                EXPECT_NE(r.output.find("this run reads"), std::string::npos) << r.output;
            }
        }
    }
    // export names .nrrd files: the label volume, and a link to the volume's data.
    fs::create_symlink(m_dir / "vol.raw", m_dir / "data_link.nrrd");
    for (const char* name : {"labels.nrrd", "data_link.nrrd"}) {
        CommandResult r =
            runCutaway("export " + m_scene.string() + " -o " + (m_dir / name).string());
        EXPECT_EQ(r.code, 2) << name << ": " << r.output;
        EXPECT_NE(r.output.find("this run reads"), std::string::npos) << r.output;
        r = runCutaway("export " + m_scene.string() + " -o " + (m_dir / "x.nrrd").string() +
                       " --labels-output " + (m_dir / name).string());
        EXPECT_EQ(r.code, 2) << name << ": " << r.output;
        EXPECT_NE(r.output.find("--labels-output: "), std::string::npos) << r.output;
    }
    expectInputsIntact();
    // The control: a file the run does not read.
    CommandResult ok = runCutaway("validate " + m_scene.string() + " --frames 0 -o " +
                                  (m_dir / "out" / "f.exr").string());
    EXPECT_EQ(ok.code, 0) << ok.output;
}

TEST_F(CliTest, ExportsTwoOutputsAreComparedAsFiles) {
    const fs::path scene = write("scene.json", R"({"version": 1,
        "volume": {"phantom": "head", "size": [16, 16, 16]}, "labels": {"phantom": true}})");
    fs::create_directories(m_dir / "sub");
    fs::create_directory_symlink(m_dir / "sub", m_dir / "link");
    const std::string cd = "env -C " + m_dir.string();
    for (const auto& [volume, labels] :
         {std::pair{"x.nrrd", "./x.nrrd"}, std::pair{"sub/x.nrrd", "link/x.nrrd"},
          std::pair{"x.nrrd", "sub/../x.nrrd"}}) {
        CommandResult r = runCutaway(
            "export " + scene.string() + " -o " + volume + " --labels-output " + labels, cd);
        EXPECT_EQ(r.code, 2) << labels << ": " << r.output;
        EXPECT_NE(r.output.find("the same file as -o"), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(m_dir / "x.nrrd"));
        EXPECT_FALSE(fs::exists(m_dir / "sub" / "x.nrrd"));
    }
    // The control: two files.
    CommandResult r =
        runCutaway("export " + scene.string() + " -o x.nrrd --labels-output sub/x.nrrd", cd);
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(fs::exists(m_dir / "x.nrrd"));
    EXPECT_TRUE(fs::exists(m_dir / "sub" / "x.nrrd"));
}

TEST_F(CliTest, APatternWithAControlCharacterIsRefusedNamingItsPointer) {
    nlohmann::json document = nlohmann::json::parse(R"({"version": 1,
        "volume": {"phantom": "head", "size": [16, 16, 16]}, "render": {"size": [16, 16]},
        "animation": {"frames": [0, 2]}})");
    for (const std::string& pattern :
         {std::string("nul/shot\0_####.exr", 18), std::string("nl/shot\n_####.exr")}) {
        SCOPED_TRACE(pattern);
        document["output"]["pattern"] = pattern;
        const fs::path scene = write("scene.json", document.dump());
        for (const char* command : {"validate", "render"}) {
            CommandResult r = runCutaway(std::string(command) + " " + scene.string());
            EXPECT_EQ(r.code, 2) << command << ": " << r.output;
            EXPECT_NE(r.output.find("scene.json: /output/pattern"), std::string::npos) << r.output;
            EXPECT_NE(r.output.find("the path holds a control character"), std::string::npos)
                << r.output;
        }
        EXPECT_EQ(files(m_dir), std::vector<std::string>{"scene.json"});
    }
    // -o takes no NUL (argv cannot hold one), but other control characters.
    const fs::path scene = write("scene.json", document.dump());
    CommandResult r =
        runCutaway("validate " + scene.string() + " -o '" + m_dir.string() + "/tab\tt_####.exr'");
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("-o \""), std::string::npos) << r.output;
}

TEST_F(CliTest, ValidateAndRenderRefuseTheSameOutputPaths) {
    const fs::path scene = write("scene.json", R"({"version": 1,
        "volume": {"phantom": "head", "size": [16, 16, 16]}, "render": {"size": [16, 16]}})");
    fs::create_symlink(m_dir / "loop1", m_dir / "loop2");
    fs::create_symlink(m_dir / "loop2", m_dir / "loop1");
    std::string deep = (m_dir / "deep").string();
    while (deep.size() < PATH_MAX)
        deep += "/abcdefgh";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {(m_dir / "loop1").string(), "too many levels of symbolic links"},
        {(m_dir / "newdir").string() + "/", "the path names a folder, not a file"},
        {deep + "/f.exr", "bytes cutaway can write (PATH_MAX"},
    };
    for (const auto& [output, why] : cases) {
        SCOPED_TRACE(why);
        const CommandResult validate = runCutaway("validate " + scene.string() + " -o " + output);
        const CommandResult render = runCutaway("render " + scene.string() + " -o " + output);
        EXPECT_EQ(validate.code, 2) << validate.output;
        EXPECT_EQ(render.code, 2) << render.output;
        EXPECT_NE(validate.output.find(why), std::string::npos) << validate.output;
        EXPECT_EQ(validate.output, render.output) << "validate and render disagree";
        EXPECT_FALSE(fs::exists(m_dir / "newdir"));
        EXPECT_FALSE(fs::exists(m_dir / "deep"));
    }
}

} // namespace cutaway::test

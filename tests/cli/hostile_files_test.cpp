// Hostile scenes, command-line values and the files a scene names, through
// the binary: each ends in exit code 2 with a short message naming the file,
// the pointer or the argument, within a time limit (a pipe that blocked or a
// stack that overflowed ended otherwise), and nothing is written.
#include "cli_util.hpp"
#include "io/named_pipe.hpp"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <string>

namespace fs = std::filesystem;

namespace cutaway::test {
namespace {

const char* kScene = R"({ "version": 1, "volume": { "phantom": "head", "size": [16, 16, 16] },
  "render": { "size": [16, 16] }, "output": { "pattern": "frames/f_####.exr" } })";

// Each line of `output` is at most `longest` characters.
bool linesAreShort(const std::string& output, std::size_t longest) {
    std::size_t start = 0;
    while (start < output.size()) {
        const std::size_t end = std::min(output.find('\n', start), output.size());
        if (end - start > longest) return false;
        start = end + 1;
    }
    return true;
}

// The example forceps model with `edit` applied to its JSON.
std::string forceps(void (*edit)(nlohmann::json&)) {
    std::ifstream in(fs::path(CUTAWAY_SOURCE_DIR) / "scenes/meshes/forceps.gltf");
    nlohmann::json model = nlohmann::json::parse(in);
    edit(model);
    return model.dump();
}

} // namespace

TEST_F(CliTest, HostileScenesAndSetValuesEndInExitTwoWithAShortMessage) {
    const fs::path scene = write("scene.json", kScene);
    const std::string deep = std::string(60000, '[') + std::string(60000, ']');
    for (const char* command : {"validate", "render", "export"}) {
        SCOPED_TRACE(command);
        const std::string extra =
            std::string(command) == "export" ? " -o " + (m_dir / "x.nrrd").string() : std::string();
        // A value 60,000 levels deep overflowed the stack printing its message.
        CommandResult r = runCutaway(std::string(command) + " " + scene.string() + extra +
                                         " --set '/render/size=" + deep + "'",
                                     "timeout -k 5 60");
        EXPECT_EQ(r.code, 2) << r.output.substr(0, 500);
        EXPECT_NE(r.output.find("--set /render/size:1:65: nesting deeper than 64 levels"),
                  std::string::npos)
            << r.output.substr(0, 500);
        EXPECT_TRUE(linesAreShort(r.output, 200)) << r.output.substr(0, 500);
    }
    // An unknown key of 100 KiB: one short line.
    nlohmann::json document = nlohmann::json::parse(kScene);
    document[std::string(100 << 10, 'k')] = 1;
    const fs::path longKey = write("long-key.json", document.dump());
    CommandResult r = runCutaway("validate " + longKey.string(), "timeout -k 5 60");
    EXPECT_EQ(r.code, 2) << r.output.substr(0, 500);
    EXPECT_NE(r.output.find("...: unknown key"), std::string::npos) << r.output.substr(0, 500);
    EXPECT_TRUE(linesAreShort(r.output, 200)) << r.output.substr(0, 500);
    // Scenes that are not regular files: /dev/zero was read without end.
    const NamedPipe pipe(m_dir / "pipe.json");
    ASSERT_TRUE(pipe.made());
    for (const fs::path& path : {fs::path("/dev/zero"), pipe.path(), m_dir}) {
        r = runCutaway("validate " + path.string(), "timeout -k 5 60");
        EXPECT_EQ(r.code, 2) << path << ": " << r.output;
        EXPECT_NE(r.output.find(path.string() + ": cannot read scene (it is "), std::string::npos)
            << r.output;
    }
    EXPECT_FALSE(pipe.wasOpened());
    // "version": 1.0 is 1 (the control: 1.5 is not).
    document = nlohmann::json::parse(kScene);
    const std::string text = document.dump();
    const std::string one = text.substr(0, text.find("\"version\":1")) + "\"version\":1.0" +
                            text.substr(text.find("\"version\":1") + 11);
    EXPECT_EQ(runCutaway("validate " + write("one.json", one).string()).code, 0);
    document["version"] = 1.5;
    EXPECT_EQ(runCutaway("validate " + write("bad.json", document.dump()).string()).code, 2);
    EXPECT_FALSE(fs::exists(m_dir / "frames"));
    EXPECT_FALSE(fs::exists(m_dir / "x.nrrd"));
}

TEST_F(CliTest, FilesAModelOrAHeaderNamesMustBeRegularFiles) {
    fs::create_directories(m_dir / "folder");
    const NamedPipe pipe(m_dir / "pipe.bin");
    ASSERT_TRUE(pipe.made());
    write("pipe.gltf", forceps([](nlohmann::json& m) { m["buffers"][0]["uri"] = "pipe.bin"; }));
    write("folder.gltf", forceps([](nlohmann::json& m) { m["buffers"][0]["uri"] = "folder"; }));
    // Written as text: dumping 20,000 levels would overflow this test's stack.
    std::string deep = forceps([](nlohmann::json&) {});
    deep.pop_back(); // the closing brace
    write("deep.gltf",
          deep + ",\"extras\":" + std::string(20000, '[') + std::string(20000, ']') + "}");
    const std::string header = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 16 16 16\n"
                               "encoding: raw\ndata file: ";
    write("folder.nhdr", header + "folder\n");
    write("pipe.nhdr", header + "pipe.bin\n");
    write("zero.nhdr", header + "/dev/zero\n");
    struct Case {
        std::string key, file, phrase;
    };
    const std::vector<Case> cases = {
        {"meshes", "pipe.gltf", "pipe.bin: cannot read a file the model names (it is a named pipe"},
        {"meshes", "folder.gltf", "folder: cannot read a file the model names (it is a folder"},
        {"meshes", "deep.gltf", "nesting deeper than 64 levels"},
        {"volume", "folder.nhdr",
         "data file 'folder' (" + (m_dir / "folder").string() +
             "): cannot read it (it is a folder"},
        {"volume", "pipe.nhdr", "): cannot read it (it is a named pipe (FIFO)"},
        {"volume", "zero.nhdr", "): cannot read it (it is a character device"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.file);
        const std::string volume = c.key == "volume"
                                       ? R"({ "file": ")" + c.file + "\" }"
                                       : R"({ "phantom": "head", "size": [16, 16, 16] })";
        const std::string meshes =
            c.key == "meshes" ? R"(, "meshes": [{ "file": ")" + c.file + "\" }]" : "";
        const fs::path scene = write("scene.json", R"({ "version": 1, "volume": )" + volume +
                                                       meshes + R"(, "render": { "size": [16, 16] },
            "output": { "pattern": "frames/f_####.exr" } })");
        for (const char* command : {"validate", "render"}) {
            CommandResult r =
                runCutaway(std::string(command) + " " + scene.string(), "timeout -k 5 60");
            EXPECT_EQ(r.code, 2) << command << ": " << r.output;
            EXPECT_NE(r.output.find(c.phrase), std::string::npos) << command << ": " << r.output;
            EXPECT_FALSE(fs::exists(m_dir / "frames"));
        }
    }
    EXPECT_FALSE(pipe.wasOpened()) << "a reader opened the pipe";
}

} // namespace cutaway::test

#include "job/output_paths.hpp"

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "job/render_job.hpp"
#include "mesh/mesh.hpp"
#include "scene/json_reader.hpp"
#include "volume/volume.hpp"

#include <algorithm>

namespace cutaway::job {
namespace {

namespace fs = std::filesystem;

void addInput(std::vector<RunInput>& inputs, const fs::path& path, const std::string& what) {
    if (path.empty()) return;
    const std::optional<FileId> id = fileIdOf(path);
    if (id && id->name.empty()) inputs.push_back({*id, path, what}); // it exists
}

void addVolumeFiles(std::vector<RunInput>& inputs, const fs::path& path, const std::string& what,
                    bool raw) {
    const std::vector<fs::path> files = raw ? std::vector<fs::path>{path} : volumeFiles(path);
    for (std::size_t i = 0; i < files.size(); ++i)
        addInput(inputs, files[i], i == 0 ? what : what + "'s data file");
}

// The place an output pattern comes from, for messages.
std::string patternSource(const Scene& scene, const SequenceOptions& options,
                          const std::string& pattern) {
    const std::string shown = "\"" + abbreviate(printable(pattern), 100) + "\"";
    if (options.overrides.outputPattern) return "-o " + shown;
    const std::string file = scene.file.empty() ? "" : scene.file.string() + ": ";
    return file + "/output/pattern " + shown;
}

// writeTarget(path), its message prefixed by `where`.
fs::path checkedTarget(const fs::path& path, const std::string& where) {
    try {
        return writeTarget(path);
    } catch (const InputError& e) {
        throw InputError(where + ": " + e.what());
    }
}

} // namespace

std::vector<RunInput> runInputs(const Scene& scene) {
    std::vector<RunInput> inputs;
    addInput(inputs, scene.file, "the scene");
    if (scene.volume.phantom.empty())
        addVolumeFiles(inputs, scene.volume.file, "the volume", scene.volume.raw.has_value());
    if (scene.labels && !scene.labels->phantom)
        addVolumeFiles(inputs, scene.labels->file, "the label volume", false);
    if (scene.labels && !scene.labels->table.empty())
        addInput(inputs, scene.labels->table, "the label table");
    for (const MeshSpec& mesh : scene.meshes) {
        std::vector<fs::path> files{mesh.file};
        try {
            files = mesh::gltfFiles(mesh.file);
        } catch (const InputError&) {
            // Reading the model for the render says what is wrong with it.
        }
        for (std::size_t i = 0; i < files.size(); ++i)
            addInput(inputs, files[i],
                     i == 0 ? mesh.name + "'s model" : "a file " + mesh.name + "'s model names");
    }
    return inputs;
}

void checkNotAnInput(const fs::path& output, const std::vector<RunInput>& inputs,
                     const std::string& where) {
    const std::optional<FileId> id = fileIdOf(output);
    if (!id || !id->name.empty()) return; // a new file is no input
    for (const RunInput& input : inputs) {
        if (input.id == *id)
            throw InputError(where + ": " + printable(output.string()) + " is " + input.what +
                             " this run reads (" + input.path.string() +
                             "); writing it would destroy it");
    }
}

void checkOutputPaths(const Scene& scene, const SequenceOptions& options) {
    const std::vector<int> frames = framesToRender(scene, options);
    if (frames.empty()) return;
    const std::string& pattern = options.overrides.outputPattern.value_or(scene.output.pattern);
    const bool png = scene.output.png || options.overrides.png;
    const std::string where = patternSource(scene, options, pattern);
    // Judged on the whole run, every shard's frames: a shard of one frame
    // with a fixed name would still replace the other shards' files.
    SequenceOptions whole = options;
    whole.shard = Shard{};
    const std::size_t runFrames = framesToRender(scene, whole).size();
    const int placeholders = framePlaceholders(pattern);
    if (runFrames > 1 && placeholders == 0)
        throw InputError(where + ": no frame number (#### or %04d) in a run of " +
                         std::to_string(runFrames) + " frames; each frame would replace the last");
    if (placeholders > 1)
        throw InputError(where + ": " + std::to_string(placeholders) +
                         " frame numbers (runs of # or %d); give exactly one");
    const std::vector<RunInput> inputs = runInputs(scene);
    for (const int frame : frames) {
        const fs::path exr = expandPattern(pattern, frame);
        if (png && previewPath(exr) == exr)
            throw InputError(where + ": the EXR file " + printable(exr.string()) +
                             " would be replaced by its PNG preview; name it .exr");
        std::vector<fs::path> paths{exr};
        if (png) paths.push_back(previewPath(exr));
        const std::string at = where + ": frame " + std::to_string(frame);
        for (const fs::path& path : paths)
            checkNotAnInput(checkedTarget(path, at), inputs, at);
    }
}

std::vector<fs::path> removeStaleTemporariesOfRun(const Scene& scene,
                                                  const SequenceOptions& options) {
    const std::string& pattern = options.overrides.outputPattern.value_or(scene.output.pattern);
    const bool png = scene.output.png || options.overrides.png;
    std::map<fs::path, std::set<std::string>> byFolder; // the files written, by folder
    for (const int frame : framesToRender(scene, options)) {
        const fs::path exr = expandPattern(pattern, frame);
        for (const fs::path& path : png ? std::vector{exr, previewPath(exr)} : std::vector{exr}) {
            const fs::path target = writeTarget(path); // where its temporary would be
            byFolder[target.parent_path()].insert(target.filename().string());
        }
    }
    std::vector<fs::path> removed;
    for (const auto& [folder, names] : byFolder) {
        const std::vector<fs::path> gone = removeStaleTemporaries(folder, names);
        removed.insert(removed.end(), gone.begin(), gone.end());
    }
    return removed;
}

void checkExportPaths(const Scene& scene, const fs::path& volume,
                      const std::optional<fs::path>& labels) {
    const std::vector<RunInput> inputs = runInputs(scene);
    const fs::path volumeTarget = checkedTarget(volume, "-o");
    checkNotAnInput(volumeTarget, inputs, "-o");
    if (!labels) return;
    const fs::path labelsTarget = checkedTarget(*labels, "--labels-output");
    checkNotAnInput(labelsTarget, inputs, "--labels-output");
    const std::optional<FileId> a = fileIdOf(volumeTarget), b = fileIdOf(labelsTarget);
    if ((a && b && *a == *b) || volumeTarget.lexically_normal() == labelsTarget.lexically_normal())
        throw InputError("--labels-output " + printable(labels->string()) +
                         ": the same file as -o " + printable(volume.string()));
}

} // namespace cutaway::job

#pragma once
// The files a run writes, checked before anything renders, the same way by
// `render` and `validate` (and by `export` for its two files): each must be
// a path cutaway can write (io/atomic_file.hpp's writeTarget), and none may
// be a file the run reads. Outputs and inputs are compared as files, not as
// text (io/input_file.hpp's FileId), so that no spelling of a path (./x,
// a symbolic link, a folder reached twice) lets an output replace an input.
#include "io/input_file.hpp"
#include "job/sequence.hpp"
#include "scene/scene.hpp"

#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace cutaway::job {

/// A file a run reads, and what it is to the run ("the volume").
struct RunInput {
    FileId id;
    std::filesystem::path path;
    std::string what;
};

/// The files a run of `scene` reads that exist: the scene file, the volume
/// (a detached NRRD header with its data file), the label volume (likewise),
/// the label table, each glTF model with the buffers and images it names.
std::vector<RunInput> runInputs(const Scene& scene);

/// Throws InputError "WHERE: PATH is the volume this run reads (...)" when
/// the file `output` names (writeTarget's) is one of `inputs`.
void checkNotAnInput(const std::filesystem::path& output, const std::vector<RunInput>& inputs,
                     const std::string& where);

/// Checks the run's output paths before anything is rendered; throws
/// InputError naming -o or the scene's /output/pattern when the pattern has
/// no frame number (#### or %04d) but the run visits several frames (each
/// would replace the last), when an EXR path is its own PNG preview (a
/// pattern ending in .png), when a frame's path is one writeTarget refuses
/// (no file name, a control character, too long, a link loop, not a regular
/// file), or when it is a file the run reads.
void checkOutputPaths(const Scene& scene, const SequenceOptions& options);

/// For --skip-existing: removes the temporaries of this run's frames (its
/// shard's, in its range) that a killed run left, as removeStaleTemporaries
/// (io/atomic_file.hpp) does: only this host's, of processes that are gone.
/// Returns the paths removed.
std::vector<std::filesystem::path> removeStaleTemporariesOfRun(const Scene& scene,
                                                               const SequenceOptions& options);

/// `cutaway export`'s files: `volume` (-o) and, when given, `labels`
/// (--labels-output) must be writable paths, not files the run of `scene`
/// reads, and not the same file as each other.
void checkExportPaths(const Scene& scene, const std::filesystem::path& volume,
                      const std::optional<std::filesystem::path>& labels);

} // namespace cutaway::job

#pragma once
// Renders the frames of a scene: a single illustration, the stages of a
// procedure or a turntable. Frames are independent, so a long sequence can be
// split over machines (shards) and resumed (skip existing files).
//
// What does not change between frames is not redone: the volume is loaded,
// uploaded and its gradients baked once per distinct /volume section (once per
// sequence unless a track animates the volume itself); the pipelines live for
// the whole run.
#include "gpu/context.hpp"
#include "io/atomic_file.hpp"
#include "io/exr.hpp"
#include "io/image.hpp"
#include "job/render_job.hpp"
#include "scene/scene.hpp"

#include <cstddef>
#include <filesystem>
#include <functional>
#include <future>
#include <optional>
#include <string>
#include <vector>

namespace cutaway::job {

struct FrameRange {
    int first = 0;
    int last = 0; ///< inclusive
};

/// Creates the folders a file's path names, if missing; throws RuntimeError
/// naming the folder when it cannot.
void createOutputFolder(const std::filesystem::path& file);

/// Writes a frame's files on a thread of their own, as a sequence does while
/// it renders the next frame: `exr` (its folder made if missing; the image's
/// channels beside the colour, when present: "operator_id", "Z", "label" and
/// the mattes) and then, when
/// given, the preview `png`, which removes the EXR if it fails (a frame's
/// files are written both or neither). The future gives the write's seconds
/// or throws what it threw.
std::future<double> writeFrameFiles(std::filesystem::path exr,
                                    std::optional<std::filesystem::path> png, Image image,
                                    ExrOptions options);

/// How many frames' files a sequence writes at once by default: one per core,
/// up to kMostWriters, and as many as kWriteQueueBytes of images allow (at
/// least one). Writes pile up only where they are slower than the render (a
/// GPU that renders a frame in milliseconds); on two cores that both render
/// (lavapipe) one frame's write is done long before the next frame is.
inline constexpr int kMostWriters = 8;
/// The most SequenceOptions::writers may ask for: each write's temporary is
/// then one a second signal can remove (io/atomic_file.hpp).
inline constexpr int kMostWritersAllowed = kTrackedTemporaries;
inline constexpr std::size_t kWriteQueueBytes = std::size_t{512} << 20;
int writesInFlight(unsigned cores, std::size_t frameBytes);

/// Parses "A..B" or "N" (frame numbers >= 0); throws InputError naming --frames.
FrameRange parseFrameRange(const std::string& text);

struct Shard {
    int index = 0;
    int count = 1;
};

/// Parses "I/N" with 0 <= I < N; throws InputError naming --shard.
Shard parseShard(const std::string& text);

/// What happened to one frame, reported as it happens.
struct FrameEvent {
    enum class Kind { Rendered, Skipped, Failed } kind = Kind::Rendered;
    int frame = 0;
    int position = 0; ///< 1-based among this run's frames
    int total = 0;    ///< frames this run will visit
    std::filesystem::path exr;
    std::optional<std::filesystem::path> png;
    double seconds = 0.0; ///< its render plus its files' write (the write overlaps the next render)
    std::string error;    ///< for Failed
    bool badInput = false; ///< Failed because of the scene (exit 2) rather than at run time
    std::vector<std::string> notes;    ///< what this frame derived (thresholds, feature bakes)
    std::vector<std::string> warnings; ///< likely mistakes in the scene, each once per run
};

struct SequenceOptions {
    std::optional<FrameRange> frames; ///< default: the scene's /animation/frames
    Shard shard;                      ///< this run renders frames with f mod count == index
    /// Leave frames whose files exist untouched, and remove the temporaries
    /// of this run's frames that a killed run left.
    bool skipExisting = false;
    bool failFast = false; ///< stop at the first failed frame
    RenderOverrides overrides;
    /// Frames whose files may be written at once while later frames render,
    /// up to kMostWritersAllowed; 0: writesInFlight(the machine's cores, the
    /// frame's bytes).
    int writers = 0;
    std::function<void(const FrameEvent&)> onFrame; ///< progress; may be empty
    std::function<bool()> stopRequested;            ///< polled between steps; may be empty
};

struct SequenceSummary {
    int rendered = 0;
    int skipped = 0;
    int failed = 0;
    bool anyBadInput = false;
    bool stopped = false;          ///< stopRequested() ended the run early
    bool writeFailed = false;      ///< a frame's files could not be written: the run stopped there
    bool resourceExceeded = false; ///< a device limit or the memory budget stopped the run
    int volumeUploads = 0; ///< volumes loaded, uploaded and baked: 1 unless /volume is animated
    /// With skipExisting: the temporaries of this run's frames that a killed
    /// run left, removed (removeStaleTemporariesOfRun, output_paths.hpp).
    std::vector<std::filesystem::path> removedTemporaries;
    std::vector<double> frameSeconds; ///< of rendered frames, as FrameEvent::seconds
    /// When each rendered frame's files were written, in seconds since the run
    /// began: the rate between the first and the last is the steady one, after
    /// the first frame's loading and bakes.
    std::vector<double> doneSeconds;
    double totalSeconds = 0.0;
};

/// The frames this run visits, in order.
std::vector<int> framesToRender(const Scene& scene, const SequenceOptions& options);

/// Renders and writes the frames, once checkOutputPaths (output_paths.hpp)
/// passes. Per-frame errors are reported through
/// onFrame and counted; a frame interrupted by stopRequested is discarded
/// (never written). A frame whose files cannot be written (disk full) fails
/// and ends the run: its temporaries are removed, earlier frames stay whole,
/// and frames being written beside it (SequenceOptions::writers) finish.
/// A frame past a device limit or the memory budget (ResourceError) also
/// ends the run.
/// Errors that concern the whole run (no device) propagate.
SequenceSummary renderSequence(const gpu::Context& ctx, const Scene& scene,
                               const SequenceOptions& options);

} // namespace cutaway::job

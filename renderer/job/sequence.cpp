#include "job/sequence.hpp"

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/exr.hpp"
#include "io/png.hpp"
#include "job/output_paths.hpp"
#include "scene/animation.hpp"

#include <algorithm>
#include <chrono>
#include <deque>
#include <future>
#include <memory>
#include <optional>
#include <regex>
#include <thread>

namespace cutaway::job {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

} // namespace

void createOutputFolder(const std::filesystem::path& file) {
    if (!file.has_parent_path()) return;
    std::error_code ec;
    std::filesystem::create_directories(file.parent_path(), ec);
    if (ec)
        throw RuntimeError("cannot create the output folder " + file.parent_path().string() + ": " +
                           ec.message());
}

FrameRange parseFrameRange(const std::string& text) {
    static const std::regex range("([0-9]{1,7})(?:\\.\\.([0-9]{1,7}))?");
    const std::string expected = "--frames: expected A..B or N with frame numbers in [0, " +
                                 std::to_string(kMaxFrame) + "], got \"" + text + "\"";
    std::smatch m;
    if (!std::regex_match(text, m, range)) throw InputError(expected);
    FrameRange r;
    r.first = std::stoi(m[1].str());
    r.last = m[2].matched ? std::stoi(m[2].str()) : r.first;
    if (r.first > kMaxFrame || r.last > kMaxFrame) throw InputError(expected);
    if (r.first > r.last) throw InputError("--frames: expected A <= B, got \"" + text + "\"");
    return r;
}

Shard parseShard(const std::string& text) {
    static const std::regex form("([0-9]{1,6})/([0-9]{1,6})");
    std::smatch m;
    if (!std::regex_match(text, m, form))
        throw InputError("--shard: expected I/N such as 0/4, got \"" + text + "\"");
    Shard s{std::stoi(m[1].str()), std::stoi(m[2].str())};
    if (s.count < 1 || s.index >= s.count)
        throw InputError("--shard: expected 0 <= I < N, got \"" + text + "\"");
    return s;
}

std::vector<int> framesToRender(const Scene& scene, const SequenceOptions& options) {
    const FrameRange range =
        options.frames.value_or(FrameRange{scene.animation.firstFrame, scene.animation.lastFrame});
    std::vector<int> frames;
    for (int f = range.first; f <= range.last; ++f)
        if (f % options.shard.count == options.shard.index) frames.push_back(f);
    return frames;
}

namespace {

// A rendered frame on its way to disk. Writing frame n overlaps rendering
// frame n + 1 (docs/design/writers.md): the files are written on another thread
// while the device renders the next frame, and where writes are slower than
// renders, several frames' files at once (writesInFlight).
// A frame's time is its own: its render (which ended before the write
// began) plus its write, not the next frame's render that the write overlaps.
struct PendingWrite {
    FrameEvent event;
    double renderSeconds = 0.0;
    std::future<double> writeSeconds;
};

// What a frame's header records as its scene: the document of this frame,
// tracks applied and /animation left out (the frame is in cutaway/frame), at
// the size it was rendered. Rendered on its own, it gives the same image.
nlohmann::json recordedScene(const Scene& frame) {
    nlohmann::json document = frame.document;
    if (document.is_object()) {
        document.erase("animation");
        document["render"]["size"] = {frame.render.width, frame.render.height};
        // The jittered offsets' seed, which defaults to the frame number.
        if (frame.render.jitter)
            document["render"]["seed"] = frame.render.seed.value_or(frame.frame);
    }
    return document;
}

ExrCompression exrCompression(Compression compression) {
    switch (compression) {
    case Compression::None:
        return ExrCompression::None;
    case Compression::Rle:
        return ExrCompression::Rle;
    case Compression::Zips:
        return ExrCompression::Zips;
    case Compression::Zip:
        return ExrCompression::Zip;
    case Compression::Piz:
        return ExrCompression::Piz;
    }
    return ExrCompression::Zip;
}

} // namespace

std::future<double> writeFrameFiles(std::filesystem::path exr,
                                    std::optional<std::filesystem::path> png, Image image,
                                    ExrOptions options) {
    auto write = [exrPath = std::move(exr), png = std::move(png), image = std::move(image),
                  options = std::move(options)]() mutable {
        const auto start = Clock::now();
        // The channels beside the colour (docs/compositing.md).
        if (!image.operatorIds.empty())
            options.channels.push_back({"operator_id", &image.operatorIds});
        if (!image.depth.empty()) options.channels.push_back({"Z", &image.depth});
        if (!image.labelIds.empty()) options.channels.push_back({"label", &image.labelIds});
        for (const ImageChannel& matte : image.mattes)
            options.channels.push_back({matte.name, &matte.values});
        createOutputFolder(exrPath);
        writeExr(exrPath, image, options);
        if (png) {
            try {
                writePng(*png, image);
            } catch (...) { // a frame's files are written both or neither (a full disk)
                std::error_code ignored;
                std::filesystem::remove(exrPath, ignored);
                throw;
            }
        }
        return secondsSince(start);
    };
    return std::async(std::launch::async, std::move(write));
}

int writesInFlight(unsigned cores, std::size_t frameBytes) {
    const std::size_t byMemory = kWriteQueueBytes / std::max<std::size_t>(frameBytes, 1);
    const std::size_t byCores = std::clamp<std::size_t>(cores, 1, kMostWriters);
    return static_cast<int>(std::clamp<std::size_t>(byMemory, 1, byCores));
}

namespace {

// One run of renderSequence: the frames rendered in order, their files
// written on other threads, each frame reported once its files are done
// (in order), the run halted where the next frames would fail the same way.
class SequenceRun {
public:
    SequenceRun(const gpu::Context& ctx, const Scene& scene, const SequenceOptions& options)
        : m_ctx(ctx), m_scene(scene), m_options(options) {}

    SequenceSummary run() {
        checkOutputPaths(m_scene, m_options);
        if (m_options.skipExisting)
            m_summary.removedTemporaries = removeStaleTemporariesOfRun(m_scene, m_options);
        const std::vector<int> frames = framesToRender(m_scene, m_options);
        for (std::size_t i = 0; i < frames.size() && !m_halted; ++i) {
            if (stopRequested()) break;
            FrameEvent event;
            event.frame = frames[i];
            event.position = static_cast<int>(i) + 1;
            event.total = static_cast<int>(frames.size());
            if (!frame(std::move(event))) break;
        }
        finishAll();
        m_summary.volumeUploads = m_renderer ? m_renderer->uploads() : 0;
        m_summary.totalSeconds = secondsSince(m_start);
        return std::move(m_summary);
    }

private:
    bool stopRequested() {
        const bool stop = m_options.stopRequested && m_options.stopRequested();
        if (stop) m_summary.stopped = true;
        return stop;
    }

    void report(FrameEvent& event) {
        if (event.kind == FrameEvent::Kind::Failed) {
            ++m_summary.failed;
            m_summary.anyBadInput = m_summary.anyBadInput || event.badInput;
            m_halted = m_halted || m_options.failFast;
        }
        if (m_options.onFrame) m_options.onFrame(event);
    }

    // Waits for the oldest pending frame's files and reports it; frames are
    // reported in order.
    void finishOldest() {
        PendingWrite p = std::move(m_pending.front());
        m_pending.pop_front();
        try {
            p.event.seconds = p.renderSeconds + p.writeSeconds.get();
            p.event.kind = FrameEvent::Kind::Rendered;
            ++m_summary.rendered;
            m_summary.frameSeconds.push_back(p.event.seconds);
            m_summary.doneSeconds.push_back(secondsSince(m_start));
        } catch (const Error& e) {
            p.event.kind = FrameEvent::Kind::Failed;
            p.event.error = e.what();
            p.event.badInput = dynamic_cast<const InputError*>(&e) != nullptr;
            p.event.seconds = p.renderSeconds;
            // A full disk, a vanished or read-only folder: later frames would
            // fail the same way after rendering for nothing.
            m_summary.writeFailed = true;
            m_halted = true;
        }
        report(p.event);
    }

    void finishAll() {
        while (!m_pending.empty())
            finishOldest();
    }

    // Reports the frames whose files are written, and waits for the oldest
    // while `most` or more are pending.
    void finishWritten(std::size_t most) {
        while (!m_pending.empty() && (m_pending.size() >= most ||
                                      m_pending.front().writeSeconds.wait_for(
                                          std::chrono::seconds(0)) == std::future_status::ready))
            finishOldest();
    }

    // Renders one frame and starts writing its files; false when the run
    // must stop (a signal, a failed write, --fail-fast).
    bool frame(FrameEvent event) {
        const auto frameStart = Clock::now();
        try {
            Scene frameScene = sceneAtFrame(m_scene, event.frame);
            applyOverrides(frameScene, m_options.overrides);
            event.exr = expandPattern(frameScene.output.pattern, event.frame);
            if (frameScene.output.png) event.png = previewPath(event.exr);
            if (m_options.skipExisting && std::filesystem::exists(event.exr) &&
                (!event.png || std::filesystem::exists(*event.png))) {
                finishAll();
                event.kind = FrameEvent::Kind::Skipped;
                ++m_summary.skipped;
                report(event);
                return true;
            }
            if (!m_renderer) m_renderer = std::make_unique<FrameRenderer>(m_ctx);
            Image image = m_renderer->render(frameScene);
            const double renderSeconds = secondsSince(frameStart);
            takeNotes(event);
            finishWritten(writers(image));
            if (stopRequested()) return false; // the frame in flight is discarded, never written
            if (m_halted) return false; // an earlier frame failed to write, or under --fail-fast
            std::future<double> write = writeFrameFiles(event.exr, event.png, std::move(image),
                                                        exrOptions(frameScene, event.frame));
            m_pending.push_back(PendingWrite{std::move(event), renderSeconds, std::move(write)});
        } catch (const Error& e) {
            failed(event, e, frameStart);
        }
        return true;
    }

    // The frame's notes and warnings, the warnings naming the scene file.
    void takeNotes(FrameEvent& event) {
        event.notes = m_renderer->takeNotes();
        for (const std::string& warning : m_renderer->takeWarnings())
            event.warnings.push_back(m_scene.file.empty() ? warning
                                                          : m_scene.file.string() + ": " + warning);
    }

    // How many frames' files may be written at once (SequenceOptions::writers).
    std::size_t writers(const Image& image) const {
        if (m_options.writers > 0)
            return static_cast<std::size_t>(std::min(m_options.writers, kMostWritersAllowed));
        return static_cast<std::size_t>(
            writesInFlight(std::thread::hardware_concurrency(), image.rgba.size() * sizeof(float)));
    }

    ExrOptions exrOptions(const Scene& frameScene, int frame) const {
        ExrOptions exr;
        exr.halfFloat = frameScene.output.pixelType == PixelType::Half;
        exr.compression = exrCompression(frameScene.output.compression);
        exr.framesPerSecond = m_scene.animation.fps;
        exr.attributes = {{"cutaway/frame", std::to_string(frame)},
                          {"cutaway/fps", nlohmann::json(m_scene.animation.fps).dump()},
                          {"cutaway/version", CUTAWAY_VERSION},
                          {"cutaway/scene", recordedScene(frameScene).dump()}};
        // The file records what the frame used, never when or how long (the
        // bakes' times go to the terminal): files are the same whichever
        // process, shard or rerun writes them.
        const std::vector<std::string> used = m_renderer->fieldsInUse();
        for (std::size_t n = 0; n < used.size(); ++n)
            exr.attributes.push_back({"cutaway/note" + std::to_string(n), used[n]});
        return exr;
    }

    void failed(FrameEvent& event, const Error& e, Clock::time_point frameStart) {
        finishAll();
        event.kind = FrameEvent::Kind::Failed;
        event.error = e.what();
        // A JSON pointer is a place in the scene file: name the file too.
        if (event.error.starts_with('/') && !m_scene.file.empty() &&
            !event.error.starts_with(m_scene.file.string()))
            event.error = m_scene.file.string() + ": " + event.error;
        event.badInput = dynamic_cast<const InputError*>(&e) != nullptr;
        event.seconds = secondsSince(frameStart);
        // Past a device limit or the memory budget, or with the device lost,
        // the next frames would fail the same way.
        if (dynamic_cast<const ResourceError*>(&e) != nullptr) {
            m_summary.resourceExceeded = true;
            m_halted = true;
        }
        report(event);
    }

    const gpu::Context& m_ctx;
    const Scene& m_scene;
    const SequenceOptions& m_options;
    const Clock::time_point m_start = Clock::now();
    SequenceSummary m_summary;
    std::unique_ptr<FrameRenderer> m_renderer; // made on the first frame that needs it
    bool m_halted = false;              // a failed frame under --fail-fast, a failed write, a limit
    std::deque<PendingWrite> m_pending; // earlier frames being written, oldest first
};

} // namespace

SequenceSummary renderSequence(const gpu::Context& ctx, const Scene& scene,
                               const SequenceOptions& options) {
    return SequenceRun(ctx, scene, options).run();
}

} // namespace cutaway::job

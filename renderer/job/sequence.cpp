#include "job/sequence.hpp"

#include "core/error.hpp"
#include "io/exr.hpp"
#include "io/png.hpp"
#include "scene/animation.hpp"

#include <chrono>
#include <future>
#include <memory>
#include <optional>
#include <regex>

namespace cutaway::job {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

void createOutputFolder(const std::filesystem::path& file) {
    if (!file.has_parent_path()) return;
    std::error_code ec;
    std::filesystem::create_directories(file.parent_path(), ec);
    if (ec)
        throw RuntimeError("cannot create the output folder " + file.parent_path().string() + ": " +
                           ec.message());
}

} // namespace

FrameRange parseFrameRange(const std::string& text) {
    static const std::regex range("([0-9]{1,7})(?:\\.\\.([0-9]{1,7}))?");
    std::smatch m;
    if (!std::regex_match(text, m, range))
        throw InputError("--frames: expected A..B or N with frame numbers >= 0, got \"" + text +
                         "\"");
    FrameRange r;
    r.first = std::stoi(m[1].str());
    r.last = m[2].matched ? std::stoi(m[2].str()) : r.first;
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
// frame n + 1 (docs/performance.md): the files are written on another thread
// while the device renders the next frame.
struct PendingWrite {
    FrameEvent event;
    Clock::time_point start;
    std::future<void> done;
};

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

PendingWrite startWrite(FrameEvent event, Clock::time_point start, Image image, ExrOptions exr) {
    auto write = [exrPath = event.exr, png = event.png, image = std::move(image),
                  exr = std::move(exr)]() mutable {
        if (!image.operatorIds.empty()) exr.channels.push_back({"operator_id", &image.operatorIds});
        createOutputFolder(exrPath);
        writeExr(exrPath, image, exr);
        if (png) writePng(*png, image);
    };
    return {std::move(event), start, std::async(std::launch::async, std::move(write))};
}

} // namespace

SequenceSummary renderSequence(const gpu::Context& ctx, const Scene& scene,
                               const SequenceOptions& options) {
    const auto runStart = Clock::now();
    const auto stop = [&] { return options.stopRequested && options.stopRequested(); };
    const std::vector<int> frames = framesToRender(scene, options);
    SequenceSummary summary;
    std::unique_ptr<FrameRenderer> renderer; // made on the first frame that needs it
    bool halted = false; // a failed frame under --fail-fast, a failed write, a limit
    const auto report = [&](FrameEvent& event) {
        if (event.kind == FrameEvent::Kind::Failed) {
            ++summary.failed;
            summary.anyBadInput = summary.anyBadInput || event.badInput;
            halted = halted || options.failFast;
        }
        if (options.onFrame) options.onFrame(event);
    };
    std::optional<PendingWrite> pending; // the previous frame, being written
    // Waits for the previous frame's files and reports it; frames are
    // reported in order.
    const auto finishPending = [&] {
        if (!pending) return;
        PendingWrite p = std::move(*pending);
        pending.reset();
        try {
            p.done.get();
            p.event.kind = FrameEvent::Kind::Rendered;
            p.event.seconds = secondsSince(p.start);
            ++summary.rendered;
            summary.frameSeconds.push_back(p.event.seconds);
            summary.doneSeconds.push_back(secondsSince(runStart));
        } catch (const Error& e) {
            p.event.kind = FrameEvent::Kind::Failed;
            p.event.error = e.what();
            p.event.badInput = dynamic_cast<const InputError*>(&e) != nullptr;
            p.event.seconds = secondsSince(p.start);
            // A full disk, a vanished or read-only folder: later frames would
            // fail the same way after rendering for nothing.
            summary.writeFailed = true;
            halted = true;
        }
        report(p.event);
    };

    for (std::size_t i = 0; i < frames.size() && !halted; ++i) {
        if (stop()) {
            summary.stopped = true;
            break;
        }
        FrameEvent event;
        event.frame = frames[i];
        event.position = static_cast<int>(i) + 1;
        event.total = static_cast<int>(frames.size());
        const auto frameStart = Clock::now();
        try {
            Scene frameScene = sceneAtFrame(scene, event.frame);
            applyOverrides(frameScene, options.overrides);
            event.exr = expandPattern(frameScene.output.pattern, event.frame);
            if (frameScene.output.png) event.png = previewPath(event.exr);
            if (options.skipExisting && std::filesystem::exists(event.exr) &&
                (!event.png || std::filesystem::exists(*event.png))) {
                finishPending();
                event.kind = FrameEvent::Kind::Skipped;
                ++summary.skipped;
                report(event);
                continue;
            }
            if (!renderer) renderer = std::make_unique<FrameRenderer>(ctx);
            Image image = renderer->render(frameScene);
            event.notes = renderer->takeNotes();
            finishPending();
            if (stop()) { // the frame in flight is discarded, never written
                summary.stopped = true;
                break;
            }
            if (halted) break; // the previous frame failed to write, or under --fail-fast
            ExrOptions exr;
            exr.halfFloat = frameScene.output.pixelType == PixelType::Half;
            exr.compression = exrCompression(frameScene.output.compression);
            exr.attributes = {{"cutaway/frame", std::to_string(event.frame)},
                              {"cutaway/fps", nlohmann::json(scene.animation.fps).dump()},
                              {"cutaway/version", CUTAWAY_VERSION},
                              {"cutaway/scene", frameScene.document.dump()}};
            for (std::size_t n = 0; n < event.notes.size(); ++n)
                exr.attributes.push_back({"cutaway/note" + std::to_string(n), event.notes[n]});
            pending = startWrite(std::move(event), frameStart, std::move(image), std::move(exr));
        } catch (const Error& e) {
            finishPending();
            event.kind = FrameEvent::Kind::Failed;
            event.error = e.what();
            // A JSON pointer is a place in the scene file: name the file too.
            if (event.error.starts_with('/') && !scene.file.empty())
                event.error = scene.file.string() + ": " + event.error;
            event.badInput = dynamic_cast<const InputError*>(&e) != nullptr;
            event.seconds = secondsSince(frameStart);
            // Past a device limit or the memory budget, or with the device
            // lost, the next frames would fail the same way.
            if (dynamic_cast<const ResourceError*>(&e) != nullptr) {
                summary.resourceExceeded = true;
                halted = true;
            }
            report(event);
        }
    }
    finishPending();
    summary.volumeUploads = renderer ? renderer->uploads() : 0;
    summary.totalSeconds = secondsSince(runStart);
    return summary;
}

} // namespace cutaway::job

#include "progress.hpp"

#include <algorithm>
#include <cstdio>

namespace cutaway::cli {

void Progress::frame(const job::FrameEvent& event) {
    using Kind = job::FrameEvent::Kind;
    if (event.kind == Kind::Failed) {
        std::fprintf(stderr, "cutaway: frame %d failed: %s\n", event.frame, event.error.c_str());
        return;
    }
    if (!m_quiet)
        for (const std::string& warning : event.warnings)
            std::fprintf(stderr, "cutaway: warning: %s\n", warning.c_str());
    if (event.kind == Kind::Rendered) {
        m_renderedSeconds += event.seconds;
        ++m_rendered;
    }
    if (!m_verbose) return;
    for (const std::string& note : event.notes)
        std::fprintf(stderr, "  %s\n", note.c_str());
    const int left = event.total - event.position;
    const double eta = m_rendered ? left * m_renderedSeconds / m_rendered : 0.0;
    if (event.kind == Kind::Skipped)
        std::fprintf(stderr, "[%d/%d] frame %d: skipped, %s exists\n", event.position, event.total,
                     event.frame, event.exr.string().c_str());
    else
        std::fprintf(stderr, "[%d/%d] frame %d: %s in %.2f s, ETA %.0f s\n", event.position,
                     event.total, event.frame, event.exr.string().c_str(), event.seconds, eta);
}

void Progress::summary(const job::SequenceSummary& s) const {
    if (!m_verbose) return;
    if (!s.removedTemporaries.empty())
        std::fprintf(stderr, "cutaway: removed %zu temporary file(s) a killed run left\n",
                     s.removedTemporaries.size());
    std::vector<double> times = s.frameSeconds;
    double median = 0.0;
    if (!times.empty()) {
        std::sort(times.begin(), times.end());
        const std::size_t n = times.size();
        median = n % 2 ? times[n / 2] : 0.5 * (times[n / 2 - 1] + times[n / 2]);
    }
    std::fprintf(stderr,
                 "cutaway: %d frame(s) rendered, %d skipped, %d failed%s in %.2f s "
                 "(median %.2f s per frame)\n",
                 s.rendered, s.skipped, s.failed,
                 s.stopped            ? ", interrupted"
                 : s.writeFailed      ? ", stopped: a frame could not be written"
                 : s.resourceExceeded ? ", stopped: past a device limit"
                                      : "",
                 s.totalSeconds, median);
}

} // namespace cutaway::cli

#pragma once
// What a sequence run prints. On a terminal: a line per frame with its time
// and an ETA, and a summary at the end. Not on a terminal, or with --quiet:
// nothing but errors and warnings (--quiet: errors only). Failed frames are
// always reported on stderr.
#include "job/sequence.hpp"

#include <chrono>

namespace cutaway::cli {

class Progress {
public:
    Progress(bool quiet, bool terminal) : m_quiet(quiet), m_verbose(!quiet && terminal) {}
    void frame(const job::FrameEvent& event);
    void summary(const job::SequenceSummary& summary) const;

private:
    bool m_quiet;
    bool m_verbose;
    double m_renderedSeconds = 0.0;
    int m_rendered = 0;
};

} // namespace cutaway::cli

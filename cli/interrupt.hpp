#pragma once
// SIGINT / SIGTERM: the first one asks the run to stop; the frame in flight is
// discarded and finished frames stay whole, since every file is written to a
// temporary name and renamed. A second signal, a quarter second or more after the
// first, ends the process at once: the temporaries in flight are unlinked and
// the signal's default action runs. One sooner counts as the same request:
// `timeout` and process managers send the signal to the process and then to
// its group, so one request often arrives twice.
namespace cutaway::cli {

void installInterruptHandlers();
/// The signal received, or 0.
int interruptSignal();

} // namespace cutaway::cli

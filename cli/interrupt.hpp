#pragma once
// Signals that end a run: SIGINT, SIGTERM, SIGHUP (the terminal hung up)
// and SIGQUIT alike. For a render, the first one asks the
// run to stop; the frame in flight is discarded and finished frames stay
// whole, since every file is written to a temporary name and renamed. A
// second signal, a quarter second or more after the first, ends the process
// at once: the temporaries in flight are unlinked and the signal's default
// action runs. One sooner counts as the same request: `timeout` and process
// managers send the signal to the process and then to its group, so one
// request often arrives twice. Either way the exit code is 128 + the signal.
// SIGPIPE is ignored: when the pipe or terminal that takes the messages is
// gone, the writes to it fail and the run goes on (its exit code still says
// whether frames failed).
namespace cutaway::cli {

/// Ignores SIGPIPE for the whole process; call at the start of main.
void ignoreBrokenPipes();
/// Installs the handlers for a run that stops between frames (render).
void installInterruptHandlers();
/// Installs handlers that end the process at the first signal, removing the
/// temporaries in flight first (export, which cannot stop half way).
void installEndingHandlers();
/// The signal received, or 0.
int interruptSignal();

} // namespace cutaway::cli

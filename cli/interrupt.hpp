#pragma once
// SIGINT / SIGTERM: the first one asks the run to stop after the frame in
// flight is discarded (finished frames stay whole, since every file is
// written to a temporary name and renamed); a second one ends the process at
// once with the default action.
namespace cutaway::cli {

void installInterruptHandlers();
/// The signal received, or 0.
int interruptSignal();

} // namespace cutaway::cli

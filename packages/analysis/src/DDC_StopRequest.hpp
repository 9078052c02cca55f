// A graceful stop of a running analysis: a batch queue's time limit or an
// operator sends SIGTERM (or SIGINT, or SIGUSR1, which Open MPI's mpirun
// forwards to the ranks without ending them), the analysis finishes the step
// it is solving, writes its checkpoint and stops (doc/user-guide.md,
// "Checkpoints and restart"). The request is a process-wide flag that a
// signal handler may set; the analysis reads it at the end of every
// converged step and agrees on it over its ranks, so a signal that reaches
// only some ranks stops all of them at the same step.
#pragma once

namespace ddc {

/// Ask the running analysis to stop after its current step. Async-signal-safe
/// (it only stores the number): call it from a host's own signal handler.
/// \param signal the signal's number (e.g. SIGTERM), > 0, for the message
void requestStop(int signal) noexcept;

/// The signal of the pending stop request (0: none).
int stopRequested() noexcept;

/// Forget a pending request (a host that goes on with another run).
void clearStopRequest() noexcept;

/// Install handlers for SIGTERM, SIGINT and SIGUSR1 that call requestStop().
/// A second signal of any of these ends the process at once (the default
/// actions are reinstated by the first). For applications (ddcontact); a host code that
/// handles signals itself calls requestStop() instead.
void installStopHandlers();

}  // namespace ddc

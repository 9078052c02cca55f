#include "DDC_StopRequest.hpp"

#include <csignal>

namespace ddc {

namespace {
volatile std::sig_atomic_t pendingSignal = 0;

extern "C" void onStopSignal(int signal) {
  pendingSignal = signal;
  // The next signal ends the process: a user who insists is obeyed.
  std::signal(SIGTERM, SIG_DFL);
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGUSR1, SIG_DFL);
}
}  // namespace

void requestStop(int signal) noexcept { pendingSignal = signal > 0 ? signal : 1; }

int stopRequested() noexcept { return pendingSignal; }

void clearStopRequest() noexcept { pendingSignal = 0; }

void installStopHandlers() {
  std::signal(SIGTERM, onStopSignal);
  std::signal(SIGINT, onStopSignal);
  std::signal(SIGUSR1, onStopSignal);
}

}  // namespace ddc

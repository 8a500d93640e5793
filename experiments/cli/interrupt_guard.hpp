#pragma once
// Ctrl-C (SIGINT) and SIGTERM during a run: while an InterruptGuard lives,
// both signals set interrupt_requested (io/trajectory_observer.hpp) and
// record which signal came. Commands pass the flag as RunConfig::stop, so
// every loop (the Lie-group schemes' and the baselines') ends after the
// current step with its statistics (status "interrupted by signal at step K,
// t = T"); lgi stress, lgi work-precision and lgi sweep then stop between
// runs, keeping what finished. The command closes its file with status
// "interrupted by signal" and returns interrupted_exit_status(): 130 after
// SIGINT, 143 after SIGTERM (exit_status.hpp).
// Construction clears the flag and installs the handler; destruction puts
// back the handlers that were there before, also when the run leaves by an
// exception.
// A command makes its guard before it creates its first output file and keeps
// it until the results are published: a signal that comes after the last step
// (while the files are being finished) then only sets the flag, the files are
// completed and the command exits 0, instead of dying half-way between
// <out>.partial and <out>.
#include "experiments/errors/exit_status.hpp"

namespace lgi::experiments {

class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

 private:
  using Handler = void (*)(int);
  Handler previous_int_;
  Handler previous_term_;
};

/// The signal that set interrupt_requested (SIGINT or SIGTERM) since the
/// last InterruptGuard was made; 0 if none.
int interrupt_signal();

/// The exit status of a run a signal ended: exit_interrupted_sigterm after
/// SIGTERM, else exit_interrupted_sigint (Ctrl-C).
ExitStatus interrupted_exit_status();

}  // namespace lgi::experiments

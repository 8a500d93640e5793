#pragma once
// Ctrl-C (SIGINT) and SIGTERM during a run: while an InterruptGuard lives,
// both signals set interrupt_requested (io/trajectory_observer.hpp). Commands
// pass it as RunConfig::stop, so every loop (the Lie-group schemes' and the
// baselines') ends after the current step with its statistics (status
// "interrupted by signal at step K, t = T"); lgi stress and lgi sweep then
// stop between runs, keeping what finished.
// Construction clears the flag and installs the handler; destruction puts
// back the handlers that were there before, also when the run leaves by an
// exception.
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

}  // namespace lgi::experiments

#include "experiments/cli/interrupt_guard.hpp"

#include <atomic>
#include <csignal>

#include "experiments/io/trajectory_observer.hpp"  // interrupt_requested

namespace lgi::experiments {
namespace {

std::atomic<int> signal_received{0};
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<bool>::is_always_lock_free,
              "a signal handler may only store to lock-free atomics");

// Only lock-free atomic stores: all a signal handler may do.
extern "C" void lgi_request_interrupt(int sig) {
  signal_received.store(sig);
  interrupt_requested.store(true);
}

}  // namespace

InterruptGuard::InterruptGuard() {
  signal_received.store(0);
  interrupt_requested.store(false);
  previous_int_ = std::signal(SIGINT, lgi_request_interrupt);
  previous_term_ = std::signal(SIGTERM, lgi_request_interrupt);
}

InterruptGuard::~InterruptGuard() {
  if (previous_int_ != SIG_ERR) std::signal(SIGINT, previous_int_);
  if (previous_term_ != SIG_ERR) std::signal(SIGTERM, previous_term_);
}

int interrupt_signal() { return signal_received.load(); }

ExitStatus interrupted_exit_status() {
  return interrupt_signal() == SIGTERM ? exit_interrupted_sigterm : exit_interrupted_sigint;
}

}  // namespace lgi::experiments

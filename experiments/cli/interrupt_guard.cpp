#include "experiments/cli/interrupt_guard.hpp"

#include <csignal>

#include "experiments/io/trajectory_observer.hpp"  // interrupt_requested

namespace lgi::experiments {
namespace {

// Only a lock-free atomic store: all a signal handler may do.
extern "C" void lgi_request_interrupt(int) { interrupt_requested.store(true); }

}  // namespace

InterruptGuard::InterruptGuard() {
  interrupt_requested.store(false);
  previous_int_ = std::signal(SIGINT, lgi_request_interrupt);
  previous_term_ = std::signal(SIGTERM, lgi_request_interrupt);
}

InterruptGuard::~InterruptGuard() {
  if (previous_int_ != SIG_ERR) std::signal(SIGINT, previous_int_);
  if (previous_term_ != SIG_ERR) std::signal(SIGTERM, previous_term_);
}

}  // namespace lgi::experiments

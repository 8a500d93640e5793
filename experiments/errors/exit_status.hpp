#pragma once
// Exit statuses of lgi (README.md, "Using lgi"), and the exception that carries a usage error to
// the top level, where it becomes one line on stderr.
#include <stdexcept>

namespace lgi::experiments {

// A run ended by a signal (cli/interrupt_guard.hpp) exits 128 + the signal's number, as a
// shell reports a process killed by it, after closing its file with status "interrupted by signal".
enum ExitStatus : int {
  exit_ok = 0,
  exit_run_failed = 1,
  exit_bad_input = 2,
  exit_interrupted_sigint = 130,   // Ctrl-C (SIGINT = 2)
  exit_interrupted_sigterm = 143,  // SIGTERM (15)
};

/// The --help footer of the commands that run and write (README.md, "Using lgi").
inline constexpr const char* exit_status_help =
    "Exit status: 0 success; 1 the run failed (blow-up, no convergence, a write that failed, e.g. a full disk; "
    "<out>.partial is kept); 2 bad command line or input, or an output that exists (without --force) or cannot be "
    "created (nothing written); 130 / 143 stopped by SIGINT (Ctrl-C) / SIGTERM after the current step, with "
    "everything so far kept in <out>.partial, status \"interrupted by signal\".";

/// A bad flag or flag combination: what() names the flag.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A run that cannot proceed for a reason that is not bad input (exit 1),
/// e.g. a scheme applied to a scene it cannot handle.
struct RunError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace lgi::experiments

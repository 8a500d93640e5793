#pragma once
// Exit statuses of lgi (README.md, "Using lgi"), and the exception that carries a usage error to
// the top level, where it becomes one line on stderr.
#include <stdexcept>

namespace lgi::experiments {

enum ExitStatus : int { exit_ok = 0, exit_run_failed = 1, exit_bad_input = 2 };

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

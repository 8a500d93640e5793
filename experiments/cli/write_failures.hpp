#pragma once
// A write that fails once an output file exists (disk full, the file-size
// limit, an I/O error) is a failed run, exit 1, not a refused output (exit 2,
// nothing written; cli.cpp): the commands that write while they run go
// through run_with_write_failures_as_run_errors, which turns the writers'
// OutputWriteError (io/h5md_writer.hpp) into RunError with the same one-line
// message naming the file. The writer has already closed the .partial file
// with a status that is not "ok" (or left it "running" if even that failed).
#include <utility>

#include "experiments/errors/exit_status.hpp"
#include "experiments/io/h5md_writer.hpp"

namespace lgi::experiments {

template <class Action>
int run_with_write_failures_as_run_errors(Action&& action) {
  try {
    return std::forward<Action>(action)();
  } catch (const OutputWriteError& e) {
    throw RunError(e.what());
  }
}

}  // namespace lgi::experiments

#pragma once
// `lgi sweep --spec SPEC --out OUT [--threads N] [--force] [--quiet]` without
// its command line (lgi.sweep, python/): the same checks, run and file.
#include <string>

namespace lgi::experiments {

struct SweepRequest {
  std::string spec, out;
  int threads = 0;  // 0: all cores
  bool force = false, quiet = true;
  std::string command_line;
};

/// Returns the exit status; throws as the subcommand does (sweep_command.cpp).
int run_sweep_request(const SweepRequest& request);

}  // namespace lgi::experiments

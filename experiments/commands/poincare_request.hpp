#pragma once
// The flags of `lgi poincare` (experiments/POINCARE.md) as fields; run without
// its command line by lgi.poincare (python/): the same checks, run and file.
#include <cstdint>
#include <optional>
#include <string>

namespace lgi::experiments {

struct PoincareRequest {
  std::string scene, out, axis, section = "richter", scheme, seeds;  // scheme: empty is the default
  std::string measure;  // empty: liouville (a Cardan top refuses the flag)
  double l = 0.0, h = 0.0, t_end = 0.0, threshold = 3.0;
  std::optional<double> dt;
  std::int64_t ics = 0, max_events = 100000;
  std::uint64_t seed = 0;
  int threads = 0;  // 0: all cores
  bool lyapunov = false, megno = false, force = false, quiet = false;
  std::string command_line;
};

/// Returns the exit status; throws as the subcommand does (poincare_command.cpp).
int run_poincare_request(const PoincareRequest& request);

}  // namespace lgi::experiments

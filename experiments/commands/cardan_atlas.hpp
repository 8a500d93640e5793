#pragma once
// The tops atlas on T³ (docs/cardan.md §9): what `lgi equilibria`,
// `lgi bifurcation` and `lgi poincare` do with a scene that has a
// [suspension] table (a Cardan-suspended top). The commands' option parsing
// stays in their own files; these run the Cardan half.
#include <cstdint>
#include <optional>
#include <string>

#include "integrators/system/scene.hpp"

namespace lgi::experiments {

struct CardanEquilibriaRequest {
  std::optional<double> l;
  int samples = 400;
  std::optional<double> omega_max;
  std::string out, command_line, subcommand = "equilibria";
  bool force = false, quiet = false;
};

/// /equilibria as for the heavy top (experiments/EQUILIBRIA.md) plus
/// cardan_angles, degenerate and pole; exit 2 unless the outer angle is cyclic.
int run_cardan_equilibria(const system::Scene& scene, const CardanEquilibriaRequest& r);

struct CardanPoincareRequest {
  double l = 0.0, h = 0.0, t_end = 0.0, dt = 0.0;
  std::int64_t ics = 0, max_events = 100000;
  std::uint64_t seed = 0;
  std::string scheme = "cardan-rk4", out, command_line;
  int threads = 1;
  bool lyapunov = false, megno = false, force = false, quiet = false;
};

/// /sweep (one row per orbit) and /events (one row per crossing) of the
/// T³ section (analysis/cardan_section.hpp).
int run_cardan_poincare(const system::Scene& scene, const CardanPoincareRequest& r);

}  // namespace lgi::experiments

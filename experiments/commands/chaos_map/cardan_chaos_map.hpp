#pragma once
// lgi chaos-map on a Cardan scene (experiments/CHAOS_MAP.md, "Cardan tops";
// docs/cardan.md §9.4): the chaotic fraction over a (key, h) plane, any
// numeric scene key varied by `--vary KEY=a:b:n` through the sweep engine's
// scene-key override (analysis/sweep_plan.hpp), the orbits drawn from the
// microcanonical measure of {H = h} (analysis/cardan_energy_draw.hpp), MEGNO
// and λ from the T³ tangent flow. OpenMP threads and MPI ranks
// (SweepRanks), bit-identical for any count; --resume from <out>.partial.
#include <cstdint>
#include <string>
#include <vector>

#include "integrators/system/scene.hpp"

namespace lgi::experiments {

/// --vary KEY=a:b:n: the key as the sweep spec names it (a component of a
/// vector key as `body.center_of_mass_2`) and its values.
struct VaryAxis {
  std::string key;
  int component = 0;  // 1..3, 0: the whole (scalar) key
  std::vector<double> values;
  std::string column() const { return component ? key + "_" + std::to_string(component) : key; }
};

/// UsageError naming --vary unless `text` is KEY=a:b:n with a key the sweep
/// spec may vary (experiments/SWEEPS.md, "What varies") of one number.
VaryAxis parse_vary_flag(const std::string& text);

struct CardanChaosMapRequest {
  std::string vary, h_range, out, command_line;
  std::int64_t ics = 0;
  double t_end = 0.0, dt = 0.0, threshold = 3.0;
  std::uint64_t seed = 0;
  int threads = 1;
  bool force = false, quiet = false, resume = false;
};

int run_cardan_chaos_map(const system::Scene& scene, const CardanChaosMapRequest& r);

}  // namespace lgi::experiments

#pragma once
// The orbits of a Cardan chaos map as they move between threads, ranks and
// runs: the fingerprint of what the orbits depend on, the gather to rank 0
// (SweepRanks::gather), and --resume from <out>.partial, whose /orbits holds
// the finished orbits (experiments/CHAOS_MAP.md, "Cardan tops").
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "experiments/commands/chaos_map/cardan_chaos_map.hpp"
#include "experiments/commands/sweep/sweep_ranks.hpp"
#include "experiments/io/table_file.hpp"
#include "integrators/system/cardan.hpp"

namespace lgi::experiments {

struct CardanMapOrbit {
  double megno = NAN, lyapunov = NAN;
  system::TorusState x0{system::Vec3::Constant(NAN), system::Vec3::Constant(NAN)};
  bool drawn = false, done = false;
};

/// What the orbits depend on (scene text, --vary, --h-range, --ics, --t-end,
/// --dt, --seed, --threshold), never the threads or ranks.
std::string chaos_map_fingerprint(const system::Scene& scene, const CardanChaosMapRequest& r);
/// /resume: its 64-bit FNV-1a hash, the one integer --resume compares.
TableGroup fingerprint_group(const std::string& fingerprint);

/// Every rank's orbits (task t ≡ rank mod ranks) onto rank 0.
void gather_orbits(std::vector<CardanMapOrbit>& orbits, SweepRanks& ranks);

/// --resume: marks done the orbits of `partial` (read on rank 0, sent to
/// every rank) and returns their count; 0 without a partial file. UsageError
/// naming --resume if it was made for another fingerprint, or is unreadable.
std::int64_t load_partial_orbits(const std::string& partial, const std::string& fingerprint, std::int64_t ics,
                                 std::vector<CardanMapOrbit>& orbits, SweepRanks& ranks);

}  // namespace lgi::experiments

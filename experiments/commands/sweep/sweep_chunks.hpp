#pragma once
// The parallel part of `lgi sweep`: the trajectories not yet done, cut into
// chunks of consecutive indices, run on OpenMP threads with dynamic
// scheduling (trajectories differ in cost), each completed chunk written to
// the partial file under one lock. Which thread runs a trajectory never
// changes its numbers: each is a function of its index alone
// (analysis/sweep_plan.hpp), and rows are stored by index.
#include <atomic>
#include <cstdint>
#include <string>

#include "experiments/analysis/sweep_trajectory.hpp"
#include "experiments/commands/sweep/sweep_ranks.hpp"
#include "experiments/io/sweep_file.hpp"

namespace lgi::experiments {

struct ChunkRunStats {
  int threads = 1, ranks = 1;
  bool interrupted = false;     // the stop flag was set: chunks in flight were dropped
  std::int64_t events = 0;      // crossings recorded by this run
  double cpu_seconds = 0.0;     // summed over this run's trajectories
  double wall_seconds = 0.0;
  double write_seconds = 0.0;   // rank 0: writing chunks to the partial file (wall)
  std::string utc_start;
};

/// Trajectories per chunk: the spec's `chunk`, else about 16 chunks per
/// thread (load balance) and at most 4096 trajectories.
std::int64_t chunk_size(const SweepSpec& spec, std::int64_t pending, int threads);

/// Runs every trajectory not marked in `done` (the partial file's, broadcast
/// from rank 0), on this rank's threads; rank 0 writes every chunk, its own
/// and those the other ranks send, to `file` (null on the other ranks).
/// Collective over the ranks.
ChunkRunStats run_chunks(const SweepSpec& spec, const SweepPlan& plan, const integrators::SchemeInfo& scheme,
                         const integrators::RunConfig& config, const SweepLayout& layout, std::vector<char> done,
                         SweepPartialFile* file, int threads, bool quiet, const std::atomic<bool>& stop,
                         SweepRanks& ranks);

}  // namespace lgi::experiments

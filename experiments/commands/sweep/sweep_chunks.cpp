#include "experiments/commands/sweep/sweep_chunks.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <utility>
#include <vector>

#include "experiments/cli/sweep_progress.hpp"

namespace lgi::experiments {

namespace {

struct Range {
  std::int64_t first, rows;
};

/// The pending indices, as chunks of at most `size` consecutive indices.
std::vector<Range> pending_chunks(const std::vector<char>& done, std::int64_t size) {
  std::vector<Range> chunks;
  const auto n = static_cast<std::int64_t>(done.size());
  for (std::int64_t i = 0; i < n;) {
    if (done[static_cast<std::size_t>(i)]) {
      ++i;
      continue;
    }
    std::int64_t end = i;
    while (end < n && end - i < size && !done[static_cast<std::size_t>(end)]) ++end;
    chunks.push_back({i, end - i});
    i = end;
  }
  return chunks;
}

void append_row(SweepChunk& c, const TrajectoryRow& row) {
  c.status.push_back(row.status);
  c.steps.push_back(row.steps);
  c.rejected_steps.push_back(row.rejected_steps);
  c.event_count.push_back(row.event_count);
  c.inputs.insert(c.inputs.end(), row.inputs.begin(), row.inputs.end());
  c.cpu_seconds.push_back(row.cpu_seconds);
  c.t_final.push_back(row.t_final);
  c.angular_momentum.insert(c.angular_momentum.end(), row.angular_momentum.begin(), row.angular_momentum.end());
  c.orientation.insert(c.orientation.end(), row.orientation.begin(), row.orientation.end());
  c.gamma.insert(c.gamma.end(), row.gamma.begin(), row.gamma.end());
  c.max_errors.insert(c.max_errors.end(), row.max_errors.begin(), row.max_errors.end());
  c.reasons.push_back(row.reason);
  ++c.rows;
}

/// Called in a catch block on any thread: the first exception is rethrown after the parallel region.
void keep_first_error(std::exception_ptr& error, std::atomic<bool>& failed) {
#pragma omp critical(sweep_error)
  {
    if (!error) error = std::current_exception();
  }
  failed = true;
}

}  // namespace

std::int64_t chunk_size(const SweepSpec& spec, std::int64_t pending, int threads) {
  if (spec.chunk > 0) return spec.chunk;
  return std::clamp<std::int64_t>(pending / (16 * std::max(threads, 1)), 1, 4096);
}

ChunkRunStats run_chunks(const SweepSpec& spec, const SweepPlan& plan, const integrators::SchemeInfo& scheme,
                         const integrators::RunConfig& config, const SweepLayout& layout, SweepPartialFile& file,
                         int threads, bool quiet, const std::atomic<bool>& stop) {
  ChunkRunStats stats;
  stats.threads = threads;
  stats.utc_start = hdf5::utc_now_iso8601();
  const auto wall0 = std::chrono::steady_clock::now();
  const auto done_before = std::count(file.done().begin(), file.done().end(), char{1});
  const std::vector<Range> chunks =
      pending_chunks(file.done(), chunk_size(spec, layout.count - done_before, threads));
  SweepProgress progress(quiet, layout.count, done_before);
  std::int64_t done = done_before;
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  double cpu = 0.0;
  std::int64_t events_total = 0;
#pragma omp parallel num_threads(threads) reduction(+ : cpu, events_total)
  {
    SweepRunner runner(spec, plan, scheme, config, layout.error_names);
#pragma omp for schedule(dynamic, 1)
    for (std::size_t k = 0; k < chunks.size(); ++k) {
      if (stop.load(std::memory_order_relaxed) || failed.load()) continue;
      try {
        SweepChunk chunk;
        chunk.first = chunks[k].first;
        bool interrupted = false;
        for (std::int64_t i = chunk.first; i < chunk.first + chunks[k].rows && !interrupted; ++i) {
          const TrajectoryRow row = runner.run(i, chunk.events, &stop);
          interrupted = row.interrupted;
          append_row(chunk, row);
        }
        if (interrupted) continue;  // dropped: --resume runs this chunk again
        for (const double s : chunk.cpu_seconds) cpu += s;
        events_total += static_cast<std::int64_t>(chunk.events.size()) / event_row_width;
#pragma omp critical(sweep_partial_file)
        {
          try {  // no exception may leave a critical section
            file.write(chunk);
            done += chunk.rows;
            progress.update(done, file.failures());
          } catch (...) {
            keep_first_error(error, failed);
          }
        }
      } catch (...) {
        keep_first_error(error, failed);
      }
    }
  }
  progress.finish();
  if (error) std::rethrow_exception(error);
  stats.interrupted = stop.load();
  stats.cpu_seconds = cpu;
  stats.events = events_total;
  stats.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return stats;
}

}  // namespace lgi::experiments

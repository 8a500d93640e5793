#include "experiments/commands/sweep/sweep_chunks.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <thread>
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

/// Empties a chunk, keeping its buffers (a thread reuses one chunk: no
/// allocation, and no page faults, per chunk).
void clear_rows(SweepChunk& c) {
  c.rows = 0;
  for (auto* v : {&c.status, &c.steps, &c.rejected_steps, &c.event_count, &c.sample_count}) v->clear();
  for (auto* v : {&c.inputs, &c.cpu_seconds, &c.t_final, &c.angular_momentum, &c.orientation, &c.gamma,
                  &c.max_errors, &c.events})
    v->clear();
  c.reasons.clear();
}

void reserve_rows(SweepChunk& c, std::int64_t rows, const TrajectoryRow& row) {
  const auto n = static_cast<std::size_t>(rows);
  for (auto* v : {&c.status, &c.steps, &c.rejected_steps, &c.event_count, &c.sample_count}) v->reserve(n);
  for (auto* v : {&c.cpu_seconds, &c.t_final}) v->reserve(n);
  c.inputs.reserve(n * row.inputs.size());
  c.max_errors.reserve(n * row.max_errors.size());
  c.angular_momentum.reserve(3 * n), c.gamma.reserve(3 * n), c.orientation.reserve(4 * n);
  c.reasons.reserve(n);
}

void append_row(SweepChunk& c, const TrajectoryRow& row) {
  c.status.push_back(row.status);
  c.steps.push_back(row.steps);
  c.rejected_steps.push_back(row.rejected_steps);
  c.event_count.push_back(row.event_count);
  c.sample_count.push_back(row.sample_count);
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

namespace {

/// Rank 0's writer: the chunks of every rank go to the partial file under one lock.
class ChunkSink {
 public:
  ChunkSink(SweepPartialFile* file, SweepProgress& progress, std::int64_t done)
      : file_(file), progress_(progress), done_(done) {}
  void write(const SweepChunk& chunk) {
#pragma omp critical(sweep_partial_file)
    {
      try {  // no exception may leave a critical section
        const auto start = std::chrono::steady_clock::now();
        file_->write(chunk);
        write_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        done_ += chunk.rows;
        progress_.update(done_, file_->failures());
      } catch (...) {
        keep_first_error(error, failed);
      }
    }
  }
  /// Rank 0: writes what the other ranks sent so far. Called under the MPI lock.
  void drain(SweepRanks& ranks) {
    SweepChunk remote;
    while (ranks.receive_chunk(remote)) write(remote);
  }
  std::exception_ptr error;
  std::atomic<bool> failed{false};
  double write_seconds = 0.0;

 private:
  SweepPartialFile* file_;
  SweepProgress& progress_;
  std::int64_t done_;
};

/// Trajectories first..first+rows−1; false if the stop flag cut one short.
bool run_chunk(SweepRunner& runner, std::int64_t first, std::int64_t rows, const std::atomic<bool>& stop,
               SweepChunk& chunk) {
  clear_rows(chunk);
  chunk.first = first;
  const double cpu0 = integrators::detail::cpu_now();
  for (std::int64_t i = first; i < first + rows;) {
    // One trajectory, or several in one ensemble (SweepRunner::run_next; the same rows either way).
    const int n = runner.run_next(i, first + rows - i, chunk.events, &stop);
    for (int j = 0; j < n; ++j) {
      const TrajectoryRow& row = runner.row(j);
      if (row.interrupted) return false;
      if (i == first && j == 0) reserve_rows(chunk, rows, row);
      append_row(chunk, row);
    }
    i += n;
  }
  // The chunk's thread CPU time, shared among its trajectories in proportion
  // to their monotonic-clock times (SweepRunner::run).
  const double cpu = integrators::detail::cpu_now() - cpu0;
  double wall = 0.0;
  for (const double t : chunk.cpu_seconds) wall += t;
  if (wall > 0.0)
    for (double& t : chunk.cpu_seconds) t *= cpu / wall;
  return true;
}

}  // namespace

ChunkRunStats run_chunks(const SweepSpec& spec, const SweepPlan& plan, const integrators::SchemeInfo& scheme,
                         const integrators::RunConfig& config, const SweepLayout& layout, std::vector<char> done,
                         SweepPartialFile* file, int threads, bool quiet, const std::atomic<bool>& stop,
                         SweepRanks& ranks) {
  ChunkRunStats stats;
  stats.threads = threads;
  stats.ranks = ranks.size();
  stats.utc_start = hdf5::utc_now_iso8601();
  const auto wall0 = std::chrono::steady_clock::now();
  const auto done_before = std::count(done.begin(), done.end(), char{1});
  // One chunk size for every rank: rank 0's.
  const std::int64_t size =
      ranks.broadcast(chunk_size(spec, layout.count - done_before, threads * ranks.size()));
  const std::vector<Range> chunks = pending_chunks(done, size);
  SweepProgress progress(quiet || !ranks.root(), layout.count, done_before);
  ChunkSink sink(file, progress, done_before);
  ranks.start_counter();
  double cpu = 0.0;
  std::int64_t events_total = 0;
#pragma omp parallel num_threads(threads) reduction(+ : cpu, events_total)
  {
    SweepRunner runner(spec, plan, scheme, config, layout.error_names);
    SweepChunk chunk;
    for (;;) {
      std::int64_t k = 0;
#pragma omp critical(lgi_mpi)
      {
        try {
          k = ranks.claim_chunk();
          if (ranks.root()) sink.drain(ranks);
        } catch (...) {
          keep_first_error(sink.error, sink.failed);
        }
      }
      if (k >= static_cast<std::int64_t>(chunks.size()) || stop.load(std::memory_order_relaxed) || sink.failed) break;
      try {
        const Range& r = chunks[static_cast<std::size_t>(k)];
        if (!run_chunk(runner, r.first, r.rows, stop, chunk)) continue;  // dropped: --resume runs it again
        for (const double s : chunk.cpu_seconds) cpu += s;
        for (const std::int64_t n : chunk.event_count) events_total += n;  // crossings, not thinned-trajectory rows
        if (ranks.root()) {
          sink.write(chunk);
        } else {
#pragma omp critical(lgi_mpi)
          {
            try {
              ranks.send_chunk(chunk);
            } catch (...) {
              keep_first_error(sink.error, sink.failed);
            }
          }
        }
      } catch (...) {
        keep_first_error(sink.error, sink.failed);
      }
    }
  }
  ranks.finish(cpu, events_total);
  while (ranks.root() && !ranks.others_finished() && !sink.failed) {
    sink.drain(ranks);
    if (!ranks.others_finished()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  progress.finish();
  if (sink.error) std::rethrow_exception(sink.error);
  stats.interrupted = stop.load();
  stats.cpu_seconds = cpu + ranks.others_cpu_seconds();
  stats.events = events_total + ranks.others_events();
  stats.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  stats.write_seconds = sink.write_seconds;
  return stats;
}

}  // namespace lgi::experiments

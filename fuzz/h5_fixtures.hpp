#pragma once
// What fuzz/fuzz_h5_readers.cpp and the seed writer fuzz/h5_seeds.cpp share:
// the readers a harness input goes to (its first byte), and the layouts,
// fingerprints and CSV text the seed files were written with, so that a
// mutated seed meets each reader with everything else right.
#include <cstdint>
#include <string>
#include <vector>

#include "experiments/io/results_file.hpp"
#include "experiments/io/sweep_file.hpp"

namespace lgi::fuzz {

/// The first byte of an input, modulo reader_count; the other bytes are the file.
enum Reader : std::uint8_t {
  sweep_resume = 0,   // lgi sweep --resume: <out>.partial (SweepPartialFile), then the final file
  sweep_columns = 1,  // lgi poincare: a finished sweep file read and extended (SweepExtraColumns)
  long_time_resume = 2,  // lgi long-time --resume: <out>.partial with its checkpoints (ResultsFile::Reopen)
  reader_count = 3,
};

inline const std::string sweep_fingerprint = "fuzz sweep fingerprint";
inline const std::string long_time_fingerprint = "fuzz long-time fingerprint";

/// The sweep of the seeds: 6 trajectories, one input column, two error
/// columns, one event, thinned trajectories.
inline experiments::SweepLayout sweep_layout() {
  experiments::SweepLayout l;
  l.count = 6;
  l.inputs = {{"initial_angular_momentum", 3}};
  l.error_names = {"energy", "casimir"};
  l.event_names = {"section"};
  l.trajectories = true;
  return l;
}

/// Trajectories first..first+rows-1 as the engine would hand them over,
/// each with `crossings` crossings and one sample.
inline experiments::SweepChunk sweep_chunk(std::int64_t first, std::int64_t rows, std::int64_t crossings) {
  experiments::SweepChunk c;
  c.first = first;
  c.rows = rows;
  const auto n = static_cast<std::size_t>(rows);
  c.status.assign(n, 0);
  c.steps.assign(n, 100);
  c.rejected_steps.assign(n, 0);
  c.event_count.assign(n, crossings);
  c.sample_count.assign(n, 1);
  c.inputs.assign(3 * n, 0.5);
  c.cpu_seconds.assign(n, 1e-3);
  c.t_final.assign(n, 1.0);
  c.angular_momentum.assign(3 * n, 1.0);
  c.orientation.assign(4 * n, 0.5);
  c.gamma.assign(3 * n, 0.0);
  c.max_errors.assign(2 * n, 1e-15);
  c.reasons.assign(n, "");
  for (std::int64_t r = 0; r < rows; ++r) {
    for (std::int64_t k = 0; k <= crossings; ++k) {
      const double row[experiments::event_row_width] = {
          static_cast<double>(first + r), k < crossings ? 0.0 : -1.0, k < crossings ? 1.0 : 0.0,
          static_cast<double>(10 * (k + 1)), 0.1 * static_cast<double>(k + 1), 1, 0, 0, 1, 0, 0, 0, 0, 0, 1};
      c.events.insert(c.events.end(), row, row + experiments::event_row_width);
    }
  }
  return c;
}

/// The columns of the long-time seed: those of a free body run.
inline std::vector<experiments::Column> long_time_columns() {
  using experiments::ColumnType;
  return {{"step", ColumnType::integer, ""},       {"time", ColumnType::real, "s"},
          {"energy_error", ColumnType::real, ""},  {"energy_error_window_max", ColumnType::real, ""}};
}
inline experiments::ResultsFileOptions long_time_options() {
  experiments::ResultsFileOptions o;
  o.table = "series";
  o.block_rows = 4;
  o.chunk_rows = 4;
  return o;
}

}  // namespace lgi::fuzz

#pragma once
// The files of `lgi sweep` (layout: experiments/SWEEPS.md).
//
// While it runs, a sweep writes <out>.partial, laid out so that a SIGKILL at
// any moment leaves a file h5py opens holding every completed chunk:
//  - every /sweep column is created at the start with all its rows
//    (contiguous, space allocated at creation, status filled with −1), so
//    writing a chunk changes raw data only, never the file's metadata;
//  - a chunk's rows are written first and its status values last, each
//    followed by a flush, so a row whose status is ≥ 0 is complete;
//  - crossings go to fixed-size blocks /partial/events_<k>, each created
//    (and flushed) when the previous one is full, and a row's event_first
//    says where its crossings are.
// At the end the final file <out> is written from the partial one: /sweep in
// index order and /events sorted by trajectory index, so its contents do not
// depend on the order in which chunks completed (threads, ranks, resumes).
#include <cstdint>
#include <string>
#include <vector>

#include "experiments/io/hdf5_support.hpp"
#include "experiments/io/sweep_spec.hpp"

namespace lgi::experiments {

/// Values per crossing in the partial file: index, event, direction, step,
/// t, Π (3), q = (w, x, y, z), Γ (3). A sample of a thinned trajectory is a
/// row of the same form with event = sample_row (−1) and direction 0.
inline constexpr int event_row_width = 15;
inline constexpr int sample_row = -1;

/// The columns of a sweep's /sweep table beside the fixed ones.
struct SweepLayout {
  std::int64_t count = 0;
  std::vector<InputColumn> inputs;
  std::vector<std::string> error_names;  // "energy" → max_energy_error
  std::vector<std::string> event_names;
  bool trajectories = false;  // /trajectory: thinned trajectories (trajectory_every)
};

/// Completed trajectories first..first+rows−1, column by column.
struct SweepChunk {
  std::int64_t first = 0, rows = 0;
  std::vector<std::int64_t> status, steps, rejected_steps, event_count, sample_count;
  std::vector<double> inputs, cpu_seconds, t_final, angular_momentum, orientation, gamma, max_errors;
  std::vector<std::string> reasons;
  std::vector<double> events;  // event_row_width values per crossing or sample, in trajectory order
};

/// Text written to the final file: /parameters (results) and /provenance
/// (this run only: command line, threads, ranks, times).
struct SweepAttributes {
  std::vector<std::pair<std::string, std::string>> parameters;
  std::vector<std::pair<std::string, std::string>> provenance;
  std::vector<std::pair<std::string, double>> numbers;  // /parameters numbers (dt, tol, t_end)
};

class SweepPartialFile {
 public:
  /// Creates `path` for a new sweep. `fingerprint`: what --resume must find
  /// unchanged (the spec and scene texts, the scheme, the layout).
  SweepPartialFile(const std::string& path, const SweepLayout& layout, const std::string& fingerprint);
  /// Opens `path` to resume; OutputFileError unless it was made with the same fingerprint.
  SweepPartialFile(const std::string& path, const SweepLayout& layout, const std::string& fingerprint, bool resume);

  /// Whether row i is complete (status ≥ 0).
  const std::vector<char>& done() const { return done_; }
  std::int64_t failures() const { return failures_; }
  /// Writes a chunk and flushes (top of this file).
  void write(const SweepChunk& chunk);
  /// Writes the final file at `path` (a new file) from this one.
  void write_final(const std::string& path, const SweepAttributes& attributes);
  void close();

 private:
  [[noreturn]] void fail(const std::string& what) const;
  void create_columns();
  void read_progress();
  std::int64_t event_position(std::int64_t rows_needed);
  std::string path_;
  SweepLayout layout_;
  hdf5::Handle file_;
  std::vector<char> done_;
  std::int64_t failures_ = 0;
  bool ready_ = false;  // set up (created, or reopened and checked): failures are OutputWriteError
  std::vector<std::int64_t> block_capacity_;
  std::int64_t block_used_ = 0;  // rows used in the last block
};

}  // namespace lgi::experiments

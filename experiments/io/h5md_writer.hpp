#pragma once
// Trajectory files after H5MD 1.1 (layout as
// written: experiments/OUTPUT.md). The writer knows nothing about schemes or
// scenes: the caller says which series the file holds (TrajectoryLayout) and
// hands over one TrajectorySample per saved step.
//
// Life of a file:
//   TrajectoryWriter w(path, force, layout, provenance);  // creates <path>.partial
//   w.append(sample); ...                                 // buffered, no HDF5 call per sample
//   w.finish(diagnostics);                                // closes, renames .partial -> path
// or, when the run fails, w.abandon(diagnostics with status = the reason):
// the .partial file stays, readable, with every sample appended. A writer
// destroyed without either (an exception unwinding) abandons with status
// "interrupted", or "failed: <why>" after a write that failed. A process killed outright leaves a .partial readable up to
// its last flush, /diagnostics status "running".
//
// Samples are kept in a block buffer (structure of arrays, preallocated) and
// written with one H5Dwrite per dataset when the block is full, followed by
// H5Fflush; the buffer is also flushed when more than flush_interval_seconds
// of wall time have passed since the last flush (the clock is read every 256
// appends).
#include <Eigen/Core>
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace lgi::experiments {

/// Failure to create, write or publish an output file. what() is one line
/// naming the file.
class OutputFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A write to an output file that was already created failed (disk full, the
/// file-size limit, an I/O error): the run cannot keep its results. Thrown by
/// the writers once their file exists; the commands exit 1 on it
/// (cli/write_failures.hpp), where a refusal to create the file exits 2.
/// The .partial file keeps what was written before; its status is not "ok".
class OutputWriteError : public OutputFileError {
 public:
  using OutputFileError::OutputFileError;
};

/// One scalar time series under /observables/<name>. `unit` in the H5MD units
/// spelling ("kg m+2 s-1", "s-4", ...); empty for a dimensionless quantity
/// (then no unit attribute is written).
struct ScalarSeries {
  std::string name;
  std::string unit;
};

/// What this run's file contains beyond the series every trajectory has
/// (orientation, body angular momentum and velocity, energy, orthogonality error).
struct TrajectoryLayout {
  std::vector<ScalarSeries> scalar_invariants;  // /observables/<name>, value [n], in this order
  bool space_momentum = false;                  // /observables/angular_momentum_space, value [n][3]
  bool euler_zxz = false;                       // /particles/body/euler_zxz, value [n][1][3] (ψ, θ, φ)
};

/// Upper bound on TrajectoryLayout::scalar_invariants.size().
inline constexpr std::size_t max_scalar_invariants = 8;

/// One saved state. Plain data with no heap member: building one per step costs nothing.
struct TrajectorySample {
  std::int64_t step = 0;  // non-decreasing from sample to sample; when equal, time increases
  double time = 0.0;      // non-decreasing
  std::array<double, 4> quaternion_wxyz{1.0, 0.0, 0.0, 0.0};  // unit quaternion body -> space, scalar first
  Eigen::Vector3d angular_momentum_body = Eigen::Vector3d::Zero();  // Π
  Eigen::Vector3d angular_velocity_body = Eigen::Vector3d::Zero();  // Ω
  double energy = 0.0;
  Eigen::Vector3d angular_momentum_space = Eigen::Vector3d::Zero();  // m = RΠ; read if layout.space_momentum
  std::array<double, max_scalar_invariants> invariants{};  // in layout order
  std::size_t invariant_count = 0;  // must equal layout.scalar_invariants.size()
  double orthogonality_error = 0.0;
  std::array<double, 3> euler_zxz{};  // (ψ, θ, φ) as integrated; read if layout.euler_zxz
};

/// Attributes of /parameters. Text is written as variable-length UTF-8
/// strings (h5py reads str), numbers as float64, integers as int64.
/// The writer adds compiler, cxx_flags, build_type (from lgi/build_info.hpp),
/// hdf5_version (the library linked) and utc_start (when the writer was
/// constructed, ISO 8601 "YYYY-MM-DDTHH:MM:SSZ") unless the caller gives them.
struct Provenance {
  std::map<std::string, std::string> text_attributes;
  std::map<std::string, double> number_attributes;
  std::map<std::string, std::int64_t> integer_attributes;
};

/// Attributes of /diagnostics: counts as int64, CPU times float64,
/// status a variable-length UTF-8 string ("ok" or why the run stopped).
/// cpu_seconds is the stepping alone (the scheme and the loop);
/// output_seconds the invariants and the writing of samples (OUTPUT.md).
struct Diagnostics {
  std::int64_t steps = 0;
  std::int64_t rejected_steps = 0;
  std::int64_t rhs_evaluations = 0;
  std::int64_t newton_iterations_max = 0;
  std::int64_t newton_failures = 0;
  double cpu_seconds = 0.0;
  double output_seconds = 0.0;
  std::string status = "ok";
};

/// The diagnostics of a run from its statistics: CPU seconds are the loop's
/// minus the time spent writing (output_seconds).
template <class RunStats>
Diagnostics diagnostics_of_run(const RunStats& stats, double output_seconds) {
  Diagnostics diag;
  diag.steps = stats.steps;
  diag.rejected_steps = stats.work.rejected_steps;
  diag.rhs_evaluations = stats.work.rhs_evaluations;
  diag.newton_iterations_max = stats.work.newton_iterations_max;
  diag.newton_failures = stats.work.newton_failures;
  diag.output_seconds = output_seconds;
  diag.cpu_seconds = stats.cpu_seconds - output_seconds > 0.0 ? stats.cpu_seconds - output_seconds : 0.0;
  diag.status = stats.status;
  return diag;
}

struct WriterOptions {
  std::size_t block_size = 4096;        // samples buffered between writes (>= 1)
  std::size_t chunk_rows = 1024;        // HDF5 chunk length along the time axis (>= 1)
  double flush_interval_seconds = 2.0;  // flush at least this often (wall time) while appending
};

class TrajectoryWriter {
 public:
  /// Creates <path>.partial (replacing a stale one) and writes the metadata.
  /// Throws OutputFileError if <path> exists and !force, if the directory is
  /// missing or not writable, or if HDF5 fails; nothing is left behind then.
  /// With force an existing <path> is untouched until finish() replaces it.
  /// Throws std::invalid_argument for a bad layout (too many invariants,
  /// empty, duplicate or reserved names, names containing '/', "." or "..").
  TrajectoryWriter(const std::string& path, bool force, const TrajectoryLayout& layout,
                   const Provenance& provenance, const WriterOptions& options = {});
  TrajectoryWriter(const TrajectoryWriter&) = delete;
  TrajectoryWriter& operator=(const TrajectoryWriter&) = delete;
  ~TrajectoryWriter();

  /// Buffers one sample. Throws std::invalid_argument if the invariant count
  /// does not match the layout or step/time go backwards, std::logic_error
  /// after finish/abandon, OutputWriteError if a flush it triggers fails.
  void append(const TrajectorySample& sample);
  /// Writes the buffered samples (one H5Dwrite per dataset) and H5Fflush.
  /// std::logic_error after finish/abandon.
  void flush();
  /// Writes the buffered samples and /diagnostics, closes the file and
  /// renames <path>.partial to <path> (without force: refuses if <path>
  /// appeared meanwhile). Throws OutputFileError on failure, after which the
  /// file is closed and <path>.partial left; std::logic_error if already closed.
  void finish(const Diagnostics& diagnostics);
  /// The run failed: writes the buffered samples and /diagnostics
  /// (status = the reason), closes, and leaves <path>.partial. A no-op if the
  /// file is already closed (after finish, even a finish that failed), so it
  /// is safe in a catch block. Throws OutputFileError if the writing fails
  /// (the file is closed regardless).
  void abandon(const Diagnostics& diagnostics);

  const std::string& path() const { return path_; }
  const std::string& partial_path() const { return partial_path_; }
  /// Samples appended so far (written or buffered).
  std::int64_t samples() const { return written_ + static_cast<std::int64_t>(buffered_); }

 private:
  struct Impl;  // HDF5 handles; keeps hdf5.h out of this header

  void append_slow_path();  // full block, or every 256 appends: clock check
  // Construction steps: block buffer, /particles/body, /observables, /diagnostics.
  void size_buffers(const WriterOptions& options);
  void create_body(std::size_t chunk_rows);
  void create_observables(std::size_t chunk_rows);
  void write_running_diagnostics();
  void write_block();
  void write_diagnostics(const Diagnostics& d);
  void write_status(const std::string& status);
  void close_file();
  /// Runs `last_writes`, then closes the file; if either throws, the file is
  /// closed anyway and the first failure is rethrown.
  void write_then_close(const std::function<void()>& last_writes);
  void abandon_impl(const Diagnostics* d, const std::string& status);
  [[noreturn]] void fail(const std::string& what) const;

  std::string path_, partial_path_;
  bool force_ = false;
  TrajectoryLayout layout_;
  std::size_t block_size_ = 0;
  std::chrono::steady_clock::duration flush_interval_{};
  std::chrono::steady_clock::time_point last_flush_{};
  std::unique_ptr<Impl> impl_;
  bool open_ = false;
  bool created_ = false;       // the file exists: failures are OutputWriteError
  bool write_failed_ = false;  // a block write or flush failed: the file keeps what was written before
  std::string write_error_;    // why (the destructor's status)

  // The block buffer, structure of arrays, sized once (block_size_ rows).
  std::size_t buffered_ = 0;
  std::int64_t written_ = 0;
  bool have_last_ = false;
  std::int64_t last_step_ = 0;
  double last_time_ = 0.0;
  std::vector<std::int64_t> step_;
  std::vector<double> time_, quat_, pi_, omega_, energy_, m_space_, ortho_, euler_;
  std::vector<double> invariants_;  // invariant k of row i at [k * block_size_ + i]
};

/// The version string of the HDF5 library linked ("1.10.8").
std::string hdf5_library_version();

}  // namespace lgi::experiments

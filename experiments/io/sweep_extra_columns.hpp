#pragma once
// Columns added to a finished sweep file (`lgi poincare`, experiments/POINCARE.md):
// reads /<group>/<name> and writes new chunked columns beside the sweep
// engine's, with the same types and layout (io/sweep_hdf5.hpp).
#include <cstdint>
#include <string>
#include <vector>

namespace lgi::experiments {

class SweepExtraColumns {
 public:
  /// Opens the file at `path` for reading and writing (OutputFileError if it cannot).
  explicit SweepExtraColumns(const std::string& path);
  ~SweepExtraColumns();
  SweepExtraColumns(const SweepExtraColumns&) = delete;
  SweepExtraColumns& operator=(const SweepExtraColumns&) = delete;

  /// Rows of /<group>/<name> (−1 if absent).
  std::int64_t rows(const std::string& group, const std::string& name) const;
  /// The whole dataset, rows × width doubles (row-major).
  std::vector<double> read_real(const std::string& group, const std::string& name, int width) const;
  std::vector<std::int64_t> read_integer(const std::string& group, const std::string& name) const;
  /// A new column of rows × width doubles (float64) or of int64.
  void write_real(const std::string& group, const std::string& name, const std::vector<double>& values, int width);
  void write_integer(const std::string& group, const std::string& name, const std::vector<std::int64_t>& values);
  /// Closes the file (an error of the close is reported).
  void close();

 private:
  [[noreturn]] void fail(const std::string& what) const;
  std::string path_;
  std::int64_t file_ = -1;
};

}  // namespace lgi::experiments

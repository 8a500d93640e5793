#pragma once
// The singularity study's output: the HDF5 file (per scene and run groups,
// /results, /parameters) and the CSV beside it (experiments/SINGULARITY.md).
#include <hdf5.h>

#include <string>
#include <vector>

#include "experiments/commands/singularity/singularity_runs.hpp"
#include "experiments/io/h5md_writer.hpp"  // OutputFileError
#include "experiments/io/hdf5_support.hpp"

namespace lgi::experiments::singularity {

/// The study's file: attributes through the shared writers, plain (not
/// chunked) datasets written once. Errors once it exists: OutputWriteError
/// (exit 1) "cannot write <what> in '<path>' (kept)".
class H5 {
 public:
  explicit H5(const std::string& path)
      : path_(path), fail_([this](const std::string& what) { throw OutputWriteError(what + " in '" + path_ + "' (kept)"); }) {
    file_ = hdf5::Handle(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
    if (!file_.valid()) throw OutputFileError("cannot create '" + path + "'");
  }
  H5(const H5&) = delete;
  H5& operator=(const H5&) = delete;
  /// HDF5 writes small datasets and metadata at close: a close that fails is a failed write.
  void close() {
    if (file_.reset() < 0) fail_("cannot finish the file (a write failed; the file is incomplete)");
  }
  hid_t file() const { return file_.get(); }
  const hdf5::Fail& fail() const { return fail_; }

  /// Creates the group `path` (parents must exist).
  hdf5::Handle group(const std::string& path) { return hdf5::create_group(file(), path, fail_); }
  void text(hid_t obj, const char* name, const std::string& value) {
    hdf5::write_vlen_string(obj, name, value, /*ascii=*/false, fail_);
  }
  void number(hid_t obj, const char* name, double value) { hdf5::write_double_attribute(obj, name, value, fail_); }
  void integer(hid_t obj, const char* name, std::int64_t value) {
    hdf5::write_int_attribute(obj, name, H5T_STD_I64LE, value, fail_);
  }
  void numbers(hid_t obj, const char* name, const std::vector<double>& v) {
    hdf5::write_double_array(obj, name, v, fail_);
  }
  /// A float64 dataset of shape dims (row-major data), with an optional unit attribute.
  void dataset(hid_t parent, const char* name, const std::vector<double>& data, const std::vector<hsize_t>& dims,
               const char* unit = nullptr) {
    const hdf5::Handle d =
        write_dataset(parent, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, dims, data.data(), data.size());
    if (unit) text(d.get(), "unit", unit);
  }
  void int_dataset(hid_t parent, const char* name, const std::vector<std::int64_t>& data) {
    write_dataset(parent, name, H5T_STD_I64LE, H5T_NATIVE_INT64, {data.size()}, data.data(), data.size());
  }
  void string_dataset(hid_t parent, const char* name, const std::vector<std::string>& data) {
    std::vector<const char*> p;
    for (const auto& s : data) p.push_back(s.c_str());
    const hdf5::Handle type = hdf5::vlen_string_type(/*ascii=*/false, fail_);
    write_dataset(parent, name, type.get(), type.get(), {data.size()}, p.data(), data.size());
  }
  void flush() {
    if (H5Fflush(file(), H5F_SCOPE_GLOBAL) < 0) fail_("cannot flush");
  }

 private:
  hdf5::Handle write_dataset(hid_t parent, const char* name, hid_t file_type, hid_t memory_type,
                             const std::vector<hsize_t>& dims, const void* data, std::size_t elements) {
    hsize_t n = 1;
    for (hsize_t d : dims) n *= d;
    if (n != elements) throw OutputFileError("internal: dataset " + std::string(name) + " has the wrong size");
    const hdf5::Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
    hdf5::Handle d(H5Dcreate2(parent, name, file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
    if (!d.valid() || (n && H5Dwrite(d.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0))
      fail_(std::string("cannot write dataset ") + name);
    return d;
  }

  hdf5::QuietHdf5Errors quiet_;  // for the file's lifetime: errors arrive as OutputFileError
  std::string path_;
  hdf5::Fail fail_;
  hdf5::Handle file_;
};

/// One line of the study's table: a run of a scene, with the tol and dt of that scene.
struct SummaryRow {
  std::string scene;
  const RunRecord* r;
  double tol, dt;
};

/// /scenes/<key>: the scene, its grid, its reference and every run's group.
void write_scene_group(H5& h5, const std::string& key, const StudyScene& sc, const std::vector<double>& reference,
                       const std::vector<RunRecord>& runs);
/// /results: one row per run, column datasets; the same table as the CSV.
void write_results_table(H5& h5, const std::vector<SummaryRow>& rows);
/// The CSV beside the HDF5 file, written as <csv>.partial and published.
void write_results_csv(const std::string& csv, const std::vector<SummaryRow>& rows, bool force);

}  // namespace lgi::experiments::singularity

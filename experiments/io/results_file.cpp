// Result files of the experiment subcommands: HDF5 (C API) tables stored
// column by column, a CSV twin, .partial + rename (results_file.hpp,
// RESULTS.md). The /h5md and /parameters conventions are those of
// h5md_writer.cpp, through the same helpers (hdf5_support.hpp).
#include "experiments/io/results_file.hpp"

#include <fcntl.h>
#include <hdf5.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "experiments/io/hdf5_support.hpp"
#include "experiments/io/results_file_impl.hpp"

namespace lgi::experiments {

using hdf5::csv_number;
using hdf5::csv_text;
using hdf5::Handle;
using hdf5::hdf5_error_detail;
using hdf5::open_or_create_group;
using hdf5::QuietHdf5Errors;
using hdf5::write_vlen_string;
using results_detail::index_columns;
using results_detail::valid_name;

namespace {

static_assert(std::is_same_v<hid_t, std::int64_t>, "results_file.hpp passes hid_t as std::int64_t");

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// Refuses before touching anything, then creates both .partial files empty.
void create_partial_files(const std::string& path, const std::string& csv_path, const std::string& partial,
                          const std::string& csv_partial, bool force) {
  for (const std::string& p : {path, csv_path}) hdf5::check_output_target(p, force);
  for (const std::string& p : {partial, csv_partial}) hdf5::check_output_target(p, true);
  const std::string dir = hdf5::parent_directory(path);
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0)
    throw OutputFileError("cannot write results '" + path + "': directory '" + dir + "': " + std::strerror(errno));
  if (!S_ISDIR(st.st_mode))
    throw OutputFileError("cannot write results '" + path + "': '" + dir + "' is not a directory");
  for (const std::string& p : {partial, csv_partial}) {
    const int fd = ::open(p.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) {
      const int err = errno;
      ::unlink(partial.c_str());
      throw OutputFileError("cannot write results '" + path + "': cannot create '" + p + "': " + std::strerror(err));
    }
    ::close(fd);
  }
}

}  // namespace

// ---- free functions ---------------------------------------------------------------

ResultAttributes diagnostics_attributes(const Diagnostics& d) {
  ResultAttributes a;
  a.integer["steps"] = d.steps;
  a.integer["rejected_steps"] = d.rejected_steps;
  a.integer["rhs_evaluations"] = d.rhs_evaluations;
  a.integer["newton_iterations_max"] = d.newton_iterations_max;
  a.integer["newton_failures"] = d.newton_failures;
  a.number["cpu_seconds"] = d.cpu_seconds;
  a.number["output_seconds"] = d.output_seconds;
  a.text["status"] = d.status;
  return a;
}

std::string results_csv_path(const std::string& h5_path) {
  for (const char* ext : {".h5", ".hdf5", ".H5", ".HDF5"}) {
    const std::string e = ext;
    if (ends_with(h5_path, e) && h5_path.size() > e.size() && h5_path[h5_path.size() - e.size() - 1] != '/')
      return h5_path.substr(0, h5_path.size() - e.size()) + ".csv";
  }
  return h5_path + ".csv";
}

// ---- rows -----------------------------------------------------------------------------

std::size_t ResultRow::index(const std::string& column, ColumnType type) const {
  const auto it = index_->find(column);
  if (it == index_->end()) throw std::invalid_argument("results table: no column '" + column + "'");
  if ((*columns_)[it->second].type != type)
    throw std::invalid_argument("results table: column '" + column + "' has another type");
  return it->second;
}
void ResultRow::set(const std::string& column, double value) { cells_[index(column, ColumnType::real)] = value; }
void ResultRow::set(const std::string& column, std::int64_t value) {
  cells_[index(column, ColumnType::integer)] = value;
}
void ResultRow::set(const std::string& column, const std::string& value) {
  cells_[index(column, ColumnType::text)] = value;
}

// ---- the file ---------------------------------------------------------------------------

void ResultsFile::fail(const std::string& what) const {
  std::string msg = "cannot write results '" + partial_path_ + "': " + what;
  const std::string detail = hdf5_error_detail();
  if (!detail.empty()) msg += " (HDF5: " + detail + ")";
  if (created_) throw OutputWriteError(msg);
  throw OutputFileError(msg);
}

void ResultsFile::fail_csv() const {
  throw OutputWriteError("cannot write results '" + csv_partial_path() + "': " + std::strerror(errno));
}

ResultsFile::ResultsFile(const std::string& path, bool force, std::vector<Column> columns, ResultsFileOptions options)
    : path_(path),
      partial_path_(path + ".partial"),
      csv_path_(results_csv_path(path)),
      force_(force),
      columns_(std::move(columns)),
      options_(std::move(options)),
      impl_(std::make_unique<Impl>()) {
  index_columns(columns_, options_, index_);
  if (path.empty()) throw OutputFileError("cannot write results: empty output file name");
  const std::string csv_partial = csv_partial_path();
  create_partial_files(path_, csv_path_, partial_path_, csv_partial, force);

  QuietHdf5Errors quiet;
  auto fail_fn = [this](const std::string& what) { fail(what); };
  try {
    create_csv(csv_partial);
    impl_->file = hdf5::create_file(partial_path_, fail_fn);
    const hid_t f = impl_->file.get();
    hdf5::write_h5md_metadata(f, /*units_module=*/true, fail_fn);  // as in trajectory files
    create_table();
    impl_->diagnostics = open_or_create_group(f, "diagnostics", fail_fn);
    write_vlen_string(impl_->diagnostics.get(), "status", "running", false, fail_fn);
    if (H5Fflush(f, H5F_SCOPE_LOCAL) < 0) fail("cannot flush");
  } catch (...) {
    impl_.reset();
    ::unlink(partial_path_.c_str());
    ::unlink(csv_partial.c_str());
    throw;
  }
  open_ = created_ = true;
  buffer_.reserve(options_.block_rows);
  last_flush_ = std::chrono::steady_clock::now();
}

// The CSV twin with its header row.
void ResultsFile::create_csv(const std::string& csv_partial) {
  impl_->csv = std::fopen(csv_partial.c_str(), "w");
  if (!impl_->csv) throw OutputFileError("cannot write results '" + csv_partial + "': " + std::strerror(errno));
  std::string header;
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    if (i) header += ',';
    header += csv_text(columns_[i].name);
  }
  header += '\n';
  if (std::fputs(header.c_str(), impl_->csv) < 0 || std::fflush(impl_->csv) != 0)
    throw OutputFileError("cannot write results '" + csv_partial + "': " + std::strerror(errno));
}

// /<table>: one empty, extendible dataset per column.
void ResultsFile::create_table() {
  auto fail_fn = [this](const std::string& what) { fail(what); };
  impl_->string_type = hdf5::vlen_string_type(/*ascii=*/false, fail_fn);
  impl_->table = open_or_create_group(impl_->file.get(), options_.table, fail_fn);
  for (const Column& c : columns_) {
    const hsize_t dims = 0, maxdims = H5S_UNLIMITED, chunk = options_.chunk_rows;
    Handle space(H5Screate_simple(1, &dims, &maxdims), H5Sclose);
    Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    if (!space.valid() || !dcpl.valid() || H5Pset_chunk(dcpl.get(), 1, &chunk) < 0)
      fail("cannot set up dataset /" + options_.table + "/" + c.name);
    const hid_t type = c.type == ColumnType::real      ? H5T_IEEE_F64LE
                       : c.type == ColumnType::integer ? H5T_STD_I64LE
                                                       : impl_->string_type.get();
    Handle d(H5Dcreate2(impl_->table.get(), c.name.c_str(), type, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
             H5Dclose);
    if (!d.valid()) fail("cannot create dataset /" + options_.table + "/" + c.name);
    if (!c.unit.empty()) write_vlen_string(d.get(), "unit", c.unit, /*ascii=*/true, fail_fn);
    impl_->columns.push_back(std::move(d));
  }
}

ResultsFile::~ResultsFile() {
  if (!open_) return;
  if (untouched_) {  // a reopened file never used: leave it as it was
    impl_.reset();
    return;
  }
  try {
    ResultAttributes a;
    a.text["status"] = write_failed_ ? "failed: " + write_error_ : std::string("interrupted");
    abandon(a);
  } catch (...) {  // a destructor must not throw
  }
}

void ResultsFile::write_attributes(std::int64_t group, const ResultAttributes& a) {
  auto fail_fn = [this](const std::string& what) { fail(what); };
  for (const auto& [k, v] : a.text) write_vlen_string(group, k.c_str(), v, false, fail_fn);
  for (const auto& [k, v] : a.fixed_text) hdf5::write_fixed_string(group, k.c_str(), v, fail_fn);
  for (const auto& [k, v] : a.number) hdf5::write_double_attribute(group, k.c_str(), v, fail_fn);
  for (const auto& [k, v] : a.integer) hdf5::write_int_attribute(group, k.c_str(), H5T_STD_I64LE, v, fail_fn);
  for (const auto& [k, v] : a.number_array) hdf5::write_double_array(group, k.c_str(), v, fail_fn);
}

void ResultsFile::write_parameters(const ResultAttributes& attributes) {
  if (!open_) throw std::logic_error("results '" + path_ + "': write_parameters after the file was closed");
  ResultAttributes a = attributes;
  auto add_default = [&](const std::string& key, const std::string& value) {
    if (!a.text.count(key) && !a.number.count(key) && !a.integer.count(key) && !a.number_array.count(key))
      a.text[key] = value;
  };
  for (const auto& [k, v] : hdf5::default_provenance(hdf5::utc_now_iso8601())) add_default(k, v);
  write_group("parameters", a);
}

void ResultsFile::write_group(const std::string& name, const ResultAttributes& attributes) {
  if (!open_) throw std::logic_error("results '" + path_ + "': write_group after the file was closed");
  if (!valid_name(name) || name == options_.table || name == "h5md")
    throw std::invalid_argument("results file: bad group name '" + name + "'");
  QuietHdf5Errors quiet;
  auto fail_fn = [this](const std::string& what) { fail(what); };
  Handle g = open_or_create_group(impl_->file.get(), name, fail_fn);
  write_attributes(g.get(), attributes);
  if (H5Fflush(impl_->file.get(), H5F_SCOPE_LOCAL) < 0) fail("cannot flush");
}

ResultRow ResultsFile::row() const {
  ResultRow r;
  r.columns_ = &columns_;
  r.index_ = &index_;
  r.cells_.reserve(columns_.size());
  for (const Column& c : columns_) {
    switch (c.type) {
      case ColumnType::real: r.cells_.emplace_back(std::numeric_limits<double>::quiet_NaN()); break;
      case ColumnType::integer: r.cells_.emplace_back(std::int64_t{-1}); break;
      case ColumnType::text: r.cells_.emplace_back(std::string()); break;
    }
  }
  return r;
}

void ResultsFile::append(const ResultRow& row) {
  if (!open_) throw std::logic_error("results '" + path_ + "': append after the file was closed");
  if (row.columns_ != &columns_) throw std::invalid_argument("results '" + path_ + "': row of another table");
  if (write_failed_) fail("an earlier block write failed");
  buffer_.push_back(row);
  if (buffer_.size() >= options_.block_rows) {
    flush();
  } else {
    flush_if_due();
  }
}

void ResultsFile::flush_if_due() {
  if (!open_ || buffer_.empty()) return;
  const auto interval = std::chrono::duration<double>(options_.flush_interval_seconds);
  if (std::chrono::steady_clock::now() - last_flush_ >= interval) flush();
}

void ResultsFile::write_block() {
  if (buffer_.empty()) return;
  const auto at = static_cast<hsize_t>(written_);
  const auto n = static_cast<hsize_t>(buffer_.size());
  try {
    std::vector<double> reals(n);
    std::vector<std::int64_t> ints(n);
    std::vector<const char*> texts(n);
    for (std::size_t c = 0; c < columns_.size(); ++c) {
      const Column& col = columns_[c];
      const void* data = nullptr;
      hid_t memory_type = H5I_INVALID_HID;
      for (std::size_t i = 0; i < n; ++i) {
        const auto& cell = buffer_[i].cells_[c];
        switch (col.type) {
          case ColumnType::real: reals[i] = std::get<double>(cell); break;
          case ColumnType::integer: ints[i] = std::get<std::int64_t>(cell); break;
          case ColumnType::text: texts[i] = std::get<std::string>(cell).c_str(); break;
        }
      }
      switch (col.type) {
        case ColumnType::real: data = reals.data(), memory_type = H5T_NATIVE_DOUBLE; break;
        case ColumnType::integer: data = ints.data(), memory_type = H5T_NATIVE_INT64; break;
        case ColumnType::text: data = texts.data(), memory_type = impl_->string_type.get(); break;
      }
      const std::string full = "/" + options_.table + "/" + col.name;
      const hid_t d = impl_->columns[c].get();
      const hsize_t dims = at + n;
      if (H5Dset_extent(d, &dims) < 0) fail("cannot extend " + full);
      Handle file_space(H5Dget_space(d), H5Sclose);
      Handle memory_space(H5Screate_simple(1, &n, nullptr), H5Sclose);
      if (!file_space.valid() || !memory_space.valid() ||
          H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, &at, nullptr, &n, nullptr) < 0)
        fail("cannot select rows of " + full);
      if (H5Dwrite(d, memory_type, memory_space.get(), file_space.get(), H5P_DEFAULT, data) < 0)
        fail("cannot write " + full);
    }
    std::string text;
    std::vector<std::uint64_t> hashes;
    for (const ResultRow& r : buffer_) {
      const std::size_t line = text.size();
      for (std::size_t c = 0; c < columns_.size(); ++c) {
        if (c) text += ',';
        const auto& cell = r.cells_[c];
        if (const double* x = std::get_if<double>(&cell)) text += csv_number(*x);
        else if (const std::int64_t* k = std::get_if<std::int64_t>(&cell)) text += std::to_string(*k);
        else text += csv_text(std::get<std::string>(cell));
      }
      text += '\n';
      if (impl_->row_hashes.valid())
        hashes.push_back(results_detail::row_hash(r.cells_, std::string_view(text).substr(line)));
    }
    if (impl_->row_hashes.valid()) write_row_hashes(at, hashes);
    if (std::fputs(text.c_str(), impl_->csv) < 0) fail_csv();
  } catch (const std::exception& e) {
    write_failed_ = true;
    write_error_ = e.what();
    buffer_.clear();
    throw;
  }
  written_ += static_cast<std::int64_t>(n);
  buffer_.clear();
}

void ResultsFile::flush() {
  if (!open_) throw std::logic_error("results '" + path_ + "': flush after the file was closed");
  if (write_failed_) fail("an earlier block write failed");
  QuietHdf5Errors quiet;
  write_block();
  try {
    if (H5Fflush(impl_->file.get(), H5F_SCOPE_LOCAL) < 0) fail("cannot flush");
    if (std::fflush(impl_->csv) != 0) fail_csv();
  } catch (const std::exception& e) {  // what reached the disk is unknown: write nothing more but diagnostics
    write_failed_ = true;
    write_error_ = e.what();
    throw;
  }
  last_flush_ = std::chrono::steady_clock::now();
}

void ResultsFile::close_files() {
  open_ = false;
  impl_->columns.clear();
  impl_->row_hashes.reset();
  impl_->diagnostics.reset();
  impl_->table.reset();
  const herr_t h5 = impl_->file.reset();
  const int csv = impl_->csv ? std::fclose(impl_->csv) : 0;
  impl_->csv = nullptr;
  if (h5 < 0) fail("cannot close the HDF5 file");
  if (csv != 0) fail_csv();
}

void ResultsFile::close_after_failure() noexcept {
  if (!open_) return;
  try {
    close_files();
  } catch (...) {  // the first failure is the one reported
  }
}

void ResultsFile::finish(const ResultAttributes& diagnostics) {
  if (!open_) throw std::logic_error("results '" + path_ + "': finish after the file was closed");
  QuietHdf5Errors quiet;
  try {
    if (write_failed_) fail("an earlier block write failed");
    write_block();
    write_attributes(impl_->diagnostics.get(), diagnostics);
    close_files();
  } catch (...) {
    close_after_failure();
    throw;
  }
  hdf5::publish(csv_partial_path(), csv_path_, force_, "the results are");
  hdf5::publish(partial_path_, path_, force_, "the results are");
}

void ResultsFile::abandon(const ResultAttributes& diagnostics) {
  if (!open_) return;
  QuietHdf5Errors quiet;
  try {
    if (!write_failed_) write_block();
  } catch (const OutputFileError&) {  // keep going: the diagnostics matter more
  }
  try {
    write_attributes(impl_->diagnostics.get(), diagnostics);
    close_files();
  } catch (...) {
    close_after_failure();
    throw;
  }
}

}  // namespace lgi::experiments

// Results files reopened to resume an interrupted run, and the fixed-size
// records a run keeps its checkpoints in (results_file.hpp, "Resume";
// RESULTS.md, "long-time --resume"). The files read here were left by a run
// that may have been killed at any moment, or damaged since: every HDF5 call
// is checked, every size bounded, and anything unexpected is an
// OutputFileError naming the file (fuzz/fuzz_h5_readers.cpp feeds it any bytes).
#include <hdf5.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>

#include "experiments/io/results_file.hpp"
#include "experiments/io/results_file_impl.hpp"
#include "experiments/io/input_file.hpp"

namespace lgi::experiments {

using hdf5::Handle;

namespace {

/// The expected HDF5 type class of a column.
bool column_type_fits(hid_t type, ColumnType column) {
  switch (H5Tget_class(type)) {
    case H5T_FLOAT: return column == ColumnType::real;
    case H5T_INTEGER: return column == ColumnType::integer;
    case H5T_STRING: return column == ColumnType::text && H5Tis_variable_str(type) > 0;
    default: return false;
  }
}

/// Rows of a 1-D dataset that can be extended and shrunk (chunked, unlimited); -1 otherwise.
std::int64_t extendible_rows(hid_t dataset) {
  Handle space(H5Dget_space(dataset), H5Sclose);
  if (!space.valid() || H5Sget_simple_extent_ndims(space.get()) != 1) return -1;
  hsize_t dims = 0, maxdims = 0;
  if (H5Sget_simple_extent_dims(space.get(), &dims, &maxdims) != 1 || maxdims != H5S_UNLIMITED) return -1;
  if (dims > static_cast<hsize_t>(std::numeric_limits<std::int64_t>::max())) return -1;
  return static_cast<std::int64_t>(dims);
}

/// The record /<group>/<name> if it is one: 1-D, 8-bit unsigned, contiguous bytes.
Handle open_record(hid_t file, const std::string& group, const std::string& name, hsize_t& size) {
  const std::string path = "/" + group + "/" + name;
  if (H5Lexists(file, ("/" + group).c_str(), H5P_DEFAULT) <= 0 || H5Lexists(file, path.c_str(), H5P_DEFAULT) <= 0)
    return {};
  Handle d(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose);
  if (!d.valid()) return {};
  Handle type(H5Dget_type(d.get()), H5Tclose);
  Handle space(H5Dget_space(d.get()), H5Sclose);
  if (!type.valid() || !space.valid() || H5Tget_class(type.get()) != H5T_INTEGER || H5Tget_size(type.get()) != 1 ||
      H5Sget_simple_extent_ndims(space.get()) != 1 || H5Sget_simple_extent_dims(space.get(), &size, nullptr) != 1)
    return {};
  return d;
}

}  // namespace

ResultsFile::ResultsFile(const std::string& path, bool force, std::vector<Column> columns, ResultsFileOptions options,
                         Reopen)
    : path_(path),
      partial_path_(path + ".partial"),
      csv_path_(results_csv_path(path)),
      force_(force),
      columns_(std::move(columns)),
      options_(std::move(options)),
      impl_(std::make_unique<Impl>()) {
  results_detail::index_columns(columns_, options_, index_);
  const hdf5::QuietHdf5Errors quiet;
  try {
    if (const std::string why = regular_file_problem(partial_path_); !why.empty()) fail(why);
    if (H5Fis_hdf5(partial_path_.c_str()) <= 0) fail("not an HDF5 file, or missing");
    Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
    if (!fapl.valid() || H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG) < 0) fail("cannot open");
    // Read-only until keep_rows(): a refused file is left byte for byte as it was (an HDF5 file
    // opened for writing gets its superblock's flags rewritten when it is closed).
    impl_->file = Handle(H5Fopen(partial_path_.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose);
    if (!impl_->file.valid()) fail("cannot open");
    reopen_table();
    reopen_csv(csv_partial_path());
  } catch (...) {
    impl_.reset();
    throw;
  }
  open_ = created_ = untouched_ = true;
  buffer_.reserve(options_.block_rows);
  last_flush_ = std::chrono::steady_clock::now();
}

void ResultsFile::reopen_table() {
  auto fail_fn = [this](const std::string& what) { fail(what); };
  const hid_t f = impl_->file.get();
  const std::string table = "/" + options_.table;
  if (H5Lexists(f, table.c_str(), H5P_DEFAULT) <= 0 || H5Lexists(f, "/diagnostics", H5P_DEFAULT) <= 0)
    fail("no " + table + " table or no /diagnostics: not a results file of this command");
  impl_->table = Handle(H5Gopen2(f, table.c_str(), H5P_DEFAULT), H5Gclose);
  impl_->diagnostics = Handle(H5Gopen2(f, "/diagnostics", H5P_DEFAULT), H5Gclose);
  if (!impl_->table.valid() || !impl_->diagnostics.valid()) fail("cannot open " + table + " or /diagnostics");
  impl_->string_type = hdf5::vlen_string_type(/*ascii=*/false, fail_fn);
  std::int64_t rows = std::numeric_limits<std::int64_t>::max();
  for (const Column& c : columns_) {
    const std::string full = table + "/" + c.name;
    if (H5Lexists(impl_->table.get(), c.name.c_str(), H5P_DEFAULT) <= 0) fail("no column " + full);
    Handle d(H5Dopen2(impl_->table.get(), c.name.c_str(), H5P_DEFAULT), H5Dclose);
    Handle type(d.valid() ? H5Dget_type(d.get()) : H5I_INVALID_HID, H5Tclose);
    if (!type.valid() || !column_type_fits(type.get(), c.type)) fail("column " + full + " is not of its type");
    const std::int64_t n = extendible_rows(d.get());
    if (n < 0) fail("column " + full + " is not an extendible 1-D dataset");
    rows = std::min(rows, n);
    impl_->columns.push_back(std::move(d));
  }
  written_ = rows;
}

void ResultsFile::reopen_csv(const std::string& csv_partial) {
  impl_->csv = std::fopen(csv_partial.c_str(), "r+");
  if (!impl_->csv) throw OutputFileError("cannot resume results '" + csv_partial + "': " + std::strerror(errno));
  std::string header;
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    if (i) header += ',';
    header += hdf5::csv_text(columns_[i].name);
  }
  header += '\n';
  // Line ends outside quotes (a quoted text cell may hold a line break).
  std::string first_line;
  bool quoted = false;
  long at = 0;
  char buf[1 << 14];
  std::size_t got = 0;
  while ((got = std::fread(buf, 1, sizeof buf, impl_->csv)) > 0) {
    for (std::size_t i = 0; i < got; ++i, ++at) {
      if (csv_row_ends_.empty() && first_line.size() <= header.size()) first_line += buf[i];
      if (buf[i] == '"') quoted = !quoted;
      else if (buf[i] == '\n' && !quoted) csv_row_ends_.push_back(at + 1);
    }
  }
  if (std::ferror(impl_->csv) || csv_row_ends_.empty() || first_line != header)
    throw OutputFileError("cannot resume results '" + csv_partial + "': not the CSV of this table");
  const auto csv_rows = static_cast<std::int64_t>(csv_row_ends_.size()) - 1;
  written_ = std::min(written_, csv_rows);
}

void ResultsFile::reopen_for_writing() {
  const std::int64_t rows = written_;
  impl_->columns.clear();
  impl_->row_hashes.reset();
  impl_->diagnostics.reset();
  impl_->table.reset();
  impl_->string_type.reset();
  impl_->file.reset();
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  if (!fapl.valid() || H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG) < 0) fail("cannot open for writing");
  impl_->file = Handle(H5Fopen(partial_path_.c_str(), H5F_ACC_RDWR, fapl.get()), H5Fclose);
  if (!impl_->file.valid()) fail("cannot open for writing");
  reopen_table();
  if (!row_hash_group_.empty()) reopen_row_hashes(row_hash_group_);
  written_ = rows;
}

void ResultsFile::keep_rows(std::int64_t n) {
  if (!open_ || !buffer_.empty()) throw std::logic_error("results '" + path_ + "': keep_rows on a file in use");
  if (n < 0 || n > written_) throw std::logic_error("results '" + path_ + "': keep_rows beyond the rows present");
  const hdf5::QuietHdf5Errors quiet;
  if (untouched_) reopen_for_writing();
  auto fail_fn = [this](const std::string& what) { fail(what); };
  const auto dims = static_cast<hsize_t>(n);
  for (std::size_t c = 0; c < columns_.size(); ++c)
    if (H5Dset_extent(impl_->columns[c].get(), &dims) < 0) fail("cannot shrink /" + options_.table + "/" + columns_[c].name);
  if (impl_->row_hashes.valid() && H5Dset_extent(impl_->row_hashes.get(), &dims) < 0) fail("cannot shrink the row checksums");
  hdf5::write_vlen_string(impl_->diagnostics.get(), "status", "running", false, fail_fn);
  if (H5Fflush(impl_->file.get(), H5F_SCOPE_LOCAL) < 0) fail("cannot flush");
  const long end = csv_row_ends_[static_cast<std::size_t>(n)];
  if (std::fflush(impl_->csv) != 0 || ::ftruncate(::fileno(impl_->csv), end) != 0 ||
      std::fseek(impl_->csv, 0, SEEK_END) != 0)
    fail_csv();
  written_ = n;
  untouched_ = false;
  last_flush_ = std::chrono::steady_clock::now();
}

std::optional<std::string> ResultsFile::text_attribute(const std::string& group, const std::string& name) const {
  if (!open_) return std::nullopt;
  const hdf5::QuietHdf5Errors quiet;
  const std::string path = "/" + group;
  if (H5Lexists(impl_->file.get(), path.c_str(), H5P_DEFAULT) <= 0) return std::nullopt;
  Handle g(H5Oopen(impl_->file.get(), path.c_str(), H5P_DEFAULT), H5Oclose);
  if (!g.valid()) return std::nullopt;
  return hdf5::read_fixed_string_attribute(g.get(), name.c_str());
}

void ResultsFile::create_record(const std::string& group, const std::string& name, std::size_t bytes) {
  if (!open_) throw std::logic_error("results '" + path_ + "': create_record after the file was closed");
  const hdf5::QuietHdf5Errors quiet;
  auto fail_fn = [this](const std::string& what) { fail(what); };
  Handle g = hdf5::open_or_create_group(impl_->file.get(), group, fail_fn);
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  const unsigned char zero = 0;
  const auto n = static_cast<hsize_t>(bytes);
  Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
  if (!dcpl.valid() || !space.valid() || H5Pset_alloc_time(dcpl.get(), H5D_ALLOC_TIME_EARLY) < 0 ||
      H5Pset_fill_time(dcpl.get(), H5D_FILL_TIME_ALLOC) < 0 ||
      H5Pset_fill_value(dcpl.get(), H5T_NATIVE_UCHAR, &zero) < 0 || H5Pset_obj_track_times(dcpl.get(), false) < 0)
    fail("cannot set up record /" + group + "/" + name);
  Handle d(H5Dcreate2(g.get(), name.c_str(), H5T_STD_U8LE, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
           H5Dclose);
  if (!d.valid()) fail("cannot create record /" + group + "/" + name);
  if (H5Fflush(impl_->file.get(), H5F_SCOPE_LOCAL) < 0) fail("cannot flush");
}

void ResultsFile::write_record(const std::string& group, const std::string& name, std::size_t offset,
                               const std::vector<unsigned char>& data) {
  if (!open_) throw std::logic_error("results '" + path_ + "': write_record after the file was closed");
  const hdf5::QuietHdf5Errors quiet;
  hsize_t size = 0;
  Handle d = open_record(impl_->file.get(), group, name, size);
  const std::string full = "/" + group + "/" + name;
  if (!d.valid() || offset > size || data.size() > size - offset) fail("no record " + full + " of that size");
  const hsize_t start = offset, count = data.size();
  Handle file_space(H5Dget_space(d.get()), H5Sclose);
  Handle memory(H5Screate_simple(1, &count, nullptr), H5Sclose);
  if (!file_space.valid() || !memory.valid() ||
      H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, &start, nullptr, &count, nullptr) < 0 ||
      H5Dwrite(d.get(), H5T_NATIVE_UCHAR, memory.get(), file_space.get(), H5P_DEFAULT, data.data()) < 0)
    fail("cannot write record " + full);
  if (H5Fflush(impl_->file.get(), H5F_SCOPE_LOCAL) < 0) fail("cannot flush");
}

std::vector<unsigned char> ResultsFile::read_record(const std::string& group, const std::string& name) const {
  if (!open_) return {};
  const hdf5::QuietHdf5Errors quiet;
  hsize_t size = 0;
  Handle d = open_record(impl_->file.get(), group, name, size);
  if (!d.valid() || size == 0 || size > (hsize_t{1} << 20)) return {};  // lgi's records are a few kB
  std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
  if (H5Dread(d.get(), H5T_NATIVE_UCHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()) < 0) return {};
  return bytes;
}

}  // namespace lgi::experiments

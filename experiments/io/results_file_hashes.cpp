// Row checksums of a results file (results_file.hpp, "Row checksums"): kept
// while rows are written, checked when a run is resumed. A row that does not
// match is reported, never repaired: the resumed run refuses the file.
#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <limits>
#include <string_view>

#include "experiments/io/results_file.hpp"
#include "experiments/io/results_file_impl.hpp"

namespace lgi::experiments {

using hdf5::Handle;

namespace {
constexpr const char* dataset_name = "row_hash";
constexpr std::int64_t block = 4096;  // rows read back at a time
}  // namespace

void ResultsFile::keep_row_hashes(const std::string& group) {
  if (!open_ || written_ != 0 || !buffer_.empty())
    throw std::logic_error("results '" + path_ + "': keep_row_hashes before the first row only");
  const hdf5::QuietHdf5Errors quiet;
  auto fail_fn = [this](const std::string& what) { fail(what); };
  Handle g = hdf5::open_or_create_group(impl_->file.get(), group, fail_fn);
  const hsize_t dims = 0, maxdims = H5S_UNLIMITED, chunk = options_.chunk_rows;
  Handle space(H5Screate_simple(1, &dims, &maxdims), H5Sclose);
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  if (!space.valid() || !dcpl.valid() || H5Pset_chunk(dcpl.get(), 1, &chunk) < 0 ||
      H5Pset_obj_track_times(dcpl.get(), false) < 0)
    fail("cannot set up /" + group + "/" + dataset_name);
  row_hash_group_ = group;
  impl_->row_hashes = Handle(
      H5Dcreate2(g.get(), dataset_name, H5T_STD_U64LE, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT), H5Dclose);
  if (!impl_->row_hashes.valid()) fail("cannot create /" + group + "/" + dataset_name);
  if (H5Fflush(impl_->file.get(), H5F_SCOPE_LOCAL) < 0) fail("cannot flush");
}

void ResultsFile::write_row_hashes(std::uint64_t at, const std::vector<std::uint64_t>& hashes) {
  const hid_t d = impl_->row_hashes.get();
  const hsize_t start = at, n = hashes.size(), dims = start + n;
  if (H5Dset_extent(d, &dims) < 0) fail("cannot extend the row checksums");
  Handle file_space(H5Dget_space(d), H5Sclose);
  Handle memory_space(H5Screate_simple(1, &n, nullptr), H5Sclose);
  if (!file_space.valid() || !memory_space.valid() ||
      H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, &start, nullptr, &n, nullptr) < 0 ||
      H5Dwrite(d, H5T_NATIVE_UINT64, memory_space.get(), file_space.get(), H5P_DEFAULT, hashes.data()) < 0)
    fail("cannot write the row checksums");
}

void ResultsFile::reopen_row_hashes(const std::string& group) {
  const hdf5::QuietHdf5Errors quiet;
  auto refuse = [this](const std::string& what) {
    throw OutputFileError("cannot resume results '" + partial_path_ + "': " + what);
  };
  const std::string path = "/" + group + "/" + dataset_name;
  const hid_t f = impl_->file.get();
  if (H5Lexists(f, ("/" + group).c_str(), H5P_DEFAULT) <= 0 || H5Lexists(f, path.c_str(), H5P_DEFAULT) <= 0)
    refuse("no row checksums " + path + " (damaged, or written by an lgi without them)");
  Handle d(H5Dopen2(f, path.c_str(), H5P_DEFAULT), H5Dclose);
  Handle type(d.valid() ? H5Dget_type(d.get()) : H5I_INVALID_HID, H5Tclose);
  Handle space(d.valid() ? H5Dget_space(d.get()) : H5I_INVALID_HID, H5Sclose);
  hsize_t dims = 0, maxdims = 0;
  if (!type.valid() || !space.valid() || H5Tget_class(type.get()) != H5T_INTEGER || H5Tget_size(type.get()) != 8 ||
      H5Sget_simple_extent_ndims(space.get()) != 1 || H5Sget_simple_extent_dims(space.get(), &dims, &maxdims) != 1 ||
      maxdims != H5S_UNLIMITED || dims > static_cast<hsize_t>(std::numeric_limits<std::int64_t>::max()))
    refuse(path + " is not a table of row checksums (damaged)");
  impl_->row_hashes = std::move(d);
  row_hash_group_ = group;
  written_ = std::min(written_, static_cast<std::int64_t>(dims));  // a kill between the writes
}

std::vector<std::vector<ResultRow::Cell>> ResultsFile::read_cells(std::int64_t first, std::int64_t n) const {
  auto refuse = [this](const std::string& what) {
    throw OutputFileError("cannot resume results '" + partial_path_ + "': " + what);
  };
  std::vector<std::vector<ResultRow::Cell>> rows(static_cast<std::size_t>(n));
  const hsize_t start = static_cast<hsize_t>(first), count = static_cast<hsize_t>(n);
  std::vector<double> reals(rows.size());
  std::vector<std::int64_t> ints(rows.size());
  std::vector<char*> texts(rows.size(), nullptr);
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    const hid_t d = impl_->columns[c].get();
    Handle file_space(H5Dget_space(d), H5Sclose);
    Handle memory(H5Screate_simple(1, &count, nullptr), H5Sclose);
    const ColumnType type = columns_[c].type;
    const hid_t memory_type = type == ColumnType::real      ? H5T_NATIVE_DOUBLE
                              : type == ColumnType::integer ? H5T_NATIVE_INT64
                                                            : impl_->string_type.get();
    void* data = type == ColumnType::real      ? static_cast<void*>(reals.data())
                 : type == ColumnType::integer ? static_cast<void*>(ints.data())
                                               : static_cast<void*>(texts.data());
    if (!file_space.valid() || !memory.valid() ||
        H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, &start, nullptr, &count, nullptr) < 0 ||
        H5Dread(d, memory_type, memory.get(), file_space.get(), H5P_DEFAULT, data) < 0)
      refuse("cannot read /" + options_.table + "/" + columns_[c].name);
    for (std::size_t r = 0; r < rows.size(); ++r) {
      if (type == ColumnType::real) rows[r].emplace_back(reals[r]);
      else if (type == ColumnType::integer) rows[r].emplace_back(ints[r]);
      else rows[r].emplace_back(std::string(texts[r] ? texts[r] : ""));
    }
    if (type == ColumnType::text) H5Dvlen_reclaim(memory_type, memory.get(), H5P_DEFAULT, texts.data());
  }
  return rows;
}

std::int64_t ResultsFile::first_damaged_row(std::int64_t n) const {
  if (!open_ || !impl_->row_hashes.valid() || n < 0 || n > written_)
    throw std::logic_error("results '" + path_ + "': first_damaged_row on rows it does not hold");
  const hdf5::QuietHdf5Errors quiet;
  std::vector<std::uint64_t> stored;
  std::string line;
  for (std::int64_t a = 0; a < n; a += block) {
    const std::int64_t m = std::min(block, n - a);
    const auto cells = read_cells(a, m);
    stored.resize(static_cast<std::size_t>(m));
    const hsize_t start = static_cast<hsize_t>(a), count = static_cast<hsize_t>(m);
    Handle file_space(H5Dget_space(impl_->row_hashes.get()), H5Sclose);
    Handle memory(H5Screate_simple(1, &count, nullptr), H5Sclose);
    if (!file_space.valid() || !memory.valid() ||
        H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, &start, nullptr, &count, nullptr) < 0 ||
        H5Dread(impl_->row_hashes.get(), H5T_NATIVE_UINT64, memory.get(), file_space.get(), H5P_DEFAULT,
                stored.data()) < 0)
      throw OutputFileError("cannot resume results '" + partial_path_ + "': cannot read its row checksums");
    for (std::int64_t k = 0; k < m; ++k) {
      const auto i = static_cast<std::size_t>(a + k);
      const long from = csv_row_ends_[i], to = csv_row_ends_[i + 1];
      line.resize(static_cast<std::size_t>(to - from));
      if (::pread(::fileno(impl_->csv), line.data(), line.size(), from) != static_cast<ssize_t>(line.size()))
        throw OutputFileError("cannot resume results '" + csv_partial_path() + "': cannot read it back");
      if (results_detail::row_hash(cells[static_cast<std::size_t>(k)], line) != stored[static_cast<std::size_t>(k)])
        return a + k;
    }
  }
  return -1;
}

}  // namespace lgi::experiments

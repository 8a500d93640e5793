#pragma once
// HDF5 plumbing shared by the partial and the final sweep files
// (sweep_file.cpp, sweep_final_file.cpp); internal to io/.
#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>

#include "experiments/io/hdf5_support.hpp"

namespace lgi::experiments::sweep_hdf5 {

using hdf5::Handle;

inline constexpr std::size_t reason_width = 160;  // bytes of a reason in the partial file
inline constexpr int block_shift = 40;            // event_first = block << 40 | row in block

inline Handle space(std::int64_t rows, int width) {
  const hsize_t dims[2] = {static_cast<hsize_t>(rows), static_cast<hsize_t>(width)};
  return {H5Screate_simple(width > 1 ? 2 : 1, dims, nullptr), H5Sclose};
}

inline Handle fixed_string_type(std::size_t size) {
  Handle t(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(t.get(), std::max<std::size_t>(size, 1));
  H5Tset_strpad(t.get(), H5T_STR_NULLPAD);
  H5Tset_cset(t.get(), H5T_CSET_UTF8);
  return t;
}

/// The rows first..first+rows−1 of a dataset of `width` numbers per row.
inline Handle row_selection(hid_t dset, std::int64_t first, std::int64_t rows, int width) {
  Handle file_space(H5Dget_space(dset), H5Sclose);
  const hsize_t start[2] = {static_cast<hsize_t>(first), 0};
  const hsize_t count[2] = {static_cast<hsize_t>(rows), static_cast<hsize_t>(width)};
  H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr);
  return file_space;
}

class SweepHdf5 {
 public:
  explicit SweepHdf5(hdf5::Fail fail) : fail_(std::move(fail)) {}

  /// A dataset of rows × width, every row allocated now (contiguous, no
  /// metadata changes when written), filled with `fill` if given.
  void create_allocated(hid_t loc, const std::string& name, hid_t type, std::int64_t rows, int width,
                        const void* fill) const {
    Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    H5Pset_obj_track_times(dcpl.get(), false);
    H5Pset_alloc_time(dcpl.get(), H5D_ALLOC_TIME_EARLY);
    // Filled where a value must mean "not written yet" (status, event_first);
    // elsewhere never (unwritten rows of a new file read as zeros), which
    // spares writing every row twice.
    H5Pset_fill_time(dcpl.get(), fill ? H5D_FILL_TIME_ALLOC : H5D_FILL_TIME_NEVER);
    if (fill) H5Pset_fill_value(dcpl.get(), type, fill);
    Handle s = space(std::max<std::int64_t>(rows, 0), width);
    Handle d(H5Dcreate2(loc, name.c_str(), type, s.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT), H5Dclose);
    if (!d.valid()) fail_("cannot create dataset " + name);
  }
  /// A chunked dataset of the final file holding `rows` × width values from `data`.
  void write_whole(hid_t loc, const std::string& name, hid_t file_type, hid_t memory_type, std::int64_t rows,
                   int width, const void* data) const {
    Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    H5Pset_obj_track_times(dcpl.get(), false);
    const hsize_t chunk[2] = {static_cast<hsize_t>(std::clamp<std::int64_t>(rows, 1, 65536)),
                              static_cast<hsize_t>(width)};
    H5Pset_chunk(dcpl.get(), width > 1 ? 2 : 1, chunk);
    Handle s = space(rows, width);
    Handle d(H5Dcreate2(loc, name.c_str(), file_type, s.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT), H5Dclose);
    if (!d.valid()) fail_("cannot create dataset " + name);
    if (rows > 0 && H5Dwrite(d.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
      fail_("cannot write dataset " + name);
  }
  void write_rows(hid_t loc, const std::string& name, hid_t memory_type, std::int64_t first, std::int64_t rows,
                  int width, const void* data) const {
    if (rows == 0) return;
    Handle d(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose);
    if (!d.valid()) fail_("cannot open dataset " + name);
    Handle file_space = row_selection(d.get(), first, rows, width);
    Handle memory = space(rows, width);
    if (H5Dwrite(d.get(), memory_type, memory.get(), file_space.get(), H5P_DEFAULT, data) < 0)
      fail_("cannot write rows of " + name);
  }
  void read_rows(hid_t loc, const std::string& name, hid_t memory_type, std::int64_t first, std::int64_t rows,
                 int width, void* data) const {
    if (rows == 0) return;
    Handle d(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose);
    if (!d.valid()) fail_("cannot open dataset " + name);
    Handle file_space = row_selection(d.get(), first, rows, width);
    Handle memory = space(rows, width);
    if (H5Dread(d.get(), memory_type, memory.get(), file_space.get(), H5P_DEFAULT, data) < 0)
      fail_("cannot read rows of " + name);
  }
  std::int64_t rows_of(hid_t loc, const std::string& name) const {
    Handle d(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose);
    if (!d.valid()) return -1;
    Handle s(H5Dget_space(d.get()), H5Sclose);
    // The sweep's datasets have 1 or 2 dimensions; a file that says otherwise is not one of them.
    const int rank = s.valid() ? H5Sget_simple_extent_ndims(s.get()) : -1;
    if (rank < 1 || rank > 2) return -1;
    hsize_t dims[2] = {0, 0};
    if (H5Sget_simple_extent_dims(s.get(), dims, nullptr) != rank ||
        dims[0] > static_cast<hsize_t>(std::numeric_limits<std::int64_t>::max()))
      return -1;
    // Every value is stored (lgi writes its datasets whole, or allocates them at
    // creation): rows beyond the file's bytes are a damaged file, not memory to allocate.
    Handle t(H5Dget_type(d.get()), H5Tclose);
    const std::size_t value_bytes = t.valid() ? H5Tget_size(t.get()) : 0;
    const hsize_t width = rank == 2 ? dims[1] : 1;
    if (value_bytes == 0 || (width > 0 && dims[0] > H5Dget_storage_size(d.get()) / value_bytes / width)) return -1;
    return static_cast<std::int64_t>(dims[0]);
  }

 private:
  hdf5::Fail fail_;
};

/// The fixed /sweep columns of both files, besides inputs and errors: name, width, integer?
struct FixedColumn {
  const char* name;
  int width;
  bool integer;
};
inline constexpr FixedColumn fixed_columns[] = {
    {"status", 1, true},        {"steps", 1, true},          {"rejected_steps", 1, true},
    {"event_count", 1, true},   {"sample_count", 1, true},   {"cpu_seconds", 1, false},   {"t_final", 1, false},
    {"angular_momentum", 3, false}, {"orientation", 4, false}, {"gamma", 3, false},
};

inline std::string error_column(const std::string& name) { return "max_" + name + "_error"; }

}  // namespace lgi::experiments::sweep_hdf5

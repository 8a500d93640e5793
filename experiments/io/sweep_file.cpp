// The partial and final files of `lgi sweep` (sweep_file.hpp; layout in
// experiments/SWEEPS.md).
#include "experiments/io/sweep_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sys/statvfs.h>
#include <unistd.h>

#include "experiments/io/h5md_writer.hpp"  // OutputFileError
#include "experiments/io/hdf5_inspection.hpp"
#include "experiments/io/sweep_hdf5.hpp"
#include "experiments/io/sweep_row_hash.hpp"

namespace lgi::experiments {

using hdf5::Handle;
using namespace sweep_hdf5;

namespace {

constexpr std::int64_t first_block_rows = 4096;  // crossings in /partial/events_0

/// Refuses a sweep whose /sweep rows alone cannot fit (README.md, "Limits"): per row the fixed
/// columns (status, steps, rejected_steps, event_count, sample_count, cpu_seconds, t_final, Π,
/// q, Γ: 17 numbers), the inputs and the invariant errors, 8 bytes each, twice (the .partial and
/// the final file exist together while the final one is written). A lower bound: crossings and
/// trajectories add to it as they come. Checked against statvfs's space for unprivileged users.
void refuse_if_it_cannot_fit(const std::string& path, const SweepLayout& layout) {
  std::uint64_t numbers = 17 + layout.error_names.size();
  for (const auto& c : layout.inputs) numbers += static_cast<std::uint64_t>(std::max(1, c.width));
  const long double need = 2.0L * 8.0L * static_cast<long double>(numbers) * static_cast<long double>(layout.count);
  struct statvfs fs {};
  if (::statvfs(hdf5::parent_directory(path).c_str(), &fs) != 0) return;  // the create reports what is wrong
  const long double free_bytes = static_cast<long double>(fs.f_bavail) * static_cast<long double>(fs.f_frsize);
  if (need <= free_bytes) return;
  auto gb = [](long double b) { return std::to_string(static_cast<long long>(std::ceil(b / 1e9L))); };
  throw OutputFileError("--out: " + path + ": " + std::to_string(layout.count) + " trajectories need at least " +
                        gb(need) + " GB (the .partial and the final file) and the file system has " + gb(free_bytes) +
                        " GB free");
}


}  // namespace

void SweepPartialFile::fail(const std::string& what) const {
  const std::string line = path_ + ": " + what + " (" + hdf5::hdf5_error_detail() + ")";
  // Once the file is set up a failure is a failed write (exit 1; README, "exit statuses"): the rows
  // written so far are complete (status last), and --resume can go on from them.
  if (ready_) throw OutputWriteError(line + "; " + path_ + " is kept (free space and finish it with --resume)");
  throw OutputFileError(line);
}

SweepPartialFile::SweepPartialFile(const std::string& path, const SweepLayout& layout, const std::string& fingerprint)
    : path_(path), layout_(layout) {
  refuse_if_it_cannot_fit(path, layout);
  const hdf5::QuietHdf5Errors quiet;
  auto fail_fn = [this](const std::string& what) { fail(what); };
  file_ = hdf5::create_file(path, fail_fn, 0);  // rows go to the file as they are written
  create_columns();
  Handle partial = hdf5::create_group(file_.get(), "/partial", fail_fn);
  hdf5::write_fixed_string(partial.get(), "fingerprint", fingerprint, fail_fn);
  SweepHdf5(fail_fn).create_allocated(partial.get(), "row_hash", H5T_STD_U64LE, layout.count, 1, nullptr);
  done_.assign(static_cast<std::size_t>(layout.count), 0);
  if (H5Fflush(file_.get(), H5F_SCOPE_LOCAL) < 0) fail("cannot flush");
  ready_ = true;
}

SweepPartialFile::SweepPartialFile(const std::string& path, const SweepLayout& layout, const std::string& fingerprint,
                                   bool /*resume*/)
    : path_(path), layout_(layout) {
  const hdf5::QuietHdf5Errors quiet;
  if (!hdf5::path_exists(path))  // gone between the command's look at it and this open
    throw OutputFileError(path + ": the partial sweep was removed before it could be opened; run again without --resume");
  if (const std::string why = hdf5::inspect_in_child(path); !why.empty())
    throw OutputFileError(path + ": cannot resume the partial sweep: " + why + " (damaged); remove it");
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG);
  H5Pset_sieve_buf_size(fapl.get(), 0);
  // Read-only until every check has passed: a refused file is left byte for byte as it was (an
  // HDF5 file opened for writing gets its superblock's flags rewritten when it is closed).
  file_ = Handle(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose);
  if (!file_.valid() && !hdf5::path_exists(path))
    throw OutputFileError(path + ": the partial sweep was removed before it could be opened; run again without --resume");
  if (!file_.valid())
    throw OutputFileError(path + ": cannot open the partial sweep to resume it (a run killed before its first write "
                                 "leaves none to resume); remove it and run again without --resume");
  std::optional<std::string> stored;
  if (H5Lexists(file_.get(), "/partial", H5P_DEFAULT) > 0) {
    Handle g(H5Gopen2(file_.get(), "/partial", H5P_DEFAULT), H5Gclose);
    if (g.valid()) stored = hdf5::read_fixed_string_attribute(g.get(), "fingerprint");
  }
  if (stored != fingerprint)
    throw OutputFileError(path + ": --resume: this partial sweep was started with a different spec, scene, scheme or "
                                 "lgi version; remove it or run without --resume");
  read_progress();
  file_.reset();
  file_ = Handle(H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl.get()), H5Fclose);
  if (!file_.valid())
    throw OutputFileError(path + ": cannot open the partial sweep for writing to resume it");
  ready_ = true;
}

void SweepPartialFile::create_columns() {
  auto fail_fn = [this](const std::string& what) { fail(what); };
  const SweepHdf5 h5(fail_fn);
  Handle sweep = hdf5::create_group(file_.get(), "/sweep", fail_fn);
  const std::int64_t n = layout_.count;
  const std::int64_t not_done = -1;
  h5.create_allocated(sweep.get(), "index", H5T_STD_I64LE, n, 1, nullptr);
  for (const auto& c : layout_.inputs) h5.create_allocated(sweep.get(), c.name, H5T_IEEE_F64LE, n, c.width, nullptr);
  for (const auto& c : fixed_columns)
    h5.create_allocated(sweep.get(), c.name, c.integer ? H5T_STD_I64LE : H5T_IEEE_F64LE, n, c.width,
                        std::strcmp(c.name, "status") == 0 ? &not_done : nullptr);
  for (const auto& e : layout_.error_names)
    h5.create_allocated(sweep.get(), error_column(e), H5T_IEEE_F64LE, n, 1, nullptr);
  h5.create_allocated(sweep.get(), "event_first", H5T_STD_I64LE, n, 1, &not_done);
  Handle reason = fixed_string_type(reason_width);
  h5.create_allocated(sweep.get(), "reason", reason.get(), n, 1, nullptr);
}

void SweepPartialFile::read_progress() {
  auto fail_fn = [this](const std::string& what) { fail(what); };
  const SweepHdf5 h5(fail_fn);
  const std::int64_t n = layout_.count;
  const std::string not_partial =
      path_ + ": --resume: not a partial sweep of " + std::to_string(n) + " trajectories (or a damaged one)";
  if (H5Lexists(file_.get(), "/sweep", H5P_DEFAULT) <= 0) throw OutputFileError(not_partial);
  Handle sweep(H5Gopen2(file_.get(), "/sweep", H5P_DEFAULT), H5Gclose);
  if (!sweep.valid() || h5.rows_of(sweep.get(), "status") != n) throw OutputFileError(not_partial);
  std::vector<std::int64_t> status(static_cast<std::size_t>(n)), first(static_cast<std::size_t>(n)),
      count(static_cast<std::size_t>(n)), samples(static_cast<std::size_t>(n));
  h5.read_rows(sweep.get(), "status", H5T_NATIVE_INT64, 0, n, 1, status.data());
  h5.read_rows(sweep.get(), "event_first", H5T_NATIVE_INT64, 0, n, 1, first.data());
  h5.read_rows(sweep.get(), "event_count", H5T_NATIVE_INT64, 0, n, 1, count.data());
  h5.read_rows(sweep.get(), "sample_count", H5T_NATIVE_INT64, 0, n, 1, samples.data());
  // Blocks that exist; the last block's use is the furthest crossing of a completed row in it.
  for (int k = 0;; ++k) {
    const std::int64_t rows = h5.rows_of(file_.get(), "/partial/events_" + std::to_string(k));
    if (rows < 0) break;
    block_capacity_.push_back(rows);
  }
  const std::int64_t last = static_cast<std::int64_t>(block_capacity_.size()) - 1;
  constexpr std::int64_t in_block = (std::int64_t{1} << block_shift) - 1;
  if (h5.rows_of(file_.get(), "/partial/row_hash") != n) throw OutputFileError(not_partial);
  done_.assign(static_cast<std::size_t>(n), 0);
  const std::vector<std::int64_t> crossings = count;
  for (std::size_t i = 0; i < status.size(); ++i) {
    if (status[i] < 0) continue;
    // A completed row's crossings and samples lie inside one existing block (a damaged file's need not).
    const std::int64_t block = first[i] >> block_shift;
    if (count[i] < 0 || samples[i] < 0 || count[i] > in_block || samples[i] > in_block - count[i] ||
        (count[i] + samples[i] > 0 &&
         (first[i] < 0 || block > last ||
          (first[i] & in_block) > block_capacity_[static_cast<std::size_t>(block)] - count[i] - samples[i])))
      throw OutputFileError(not_partial);
    count[i] += samples[i];  // block rows of the trajectory
    done_[i] = 1;
    if (status[i] != 0) ++failures_;
    if (first[i] >= 0 && (first[i] >> block_shift) == last)
      block_used_ = std::max(block_used_, (first[i] & ((std::int64_t{1} << block_shift) - 1)) + count[i]);
  }
  // Every finished row against its checksum (sweep_row_hash.hpp): a damaged one is refused, not recomputed.
  if (const std::int64_t bad = first_damaged_sweep_row(h5, file_.get(), layout_, status, first, crossings, samples);
      bad >= 0)
    throw OutputFileError(path_ + ": --resume: row " + std::to_string(bad) +
                          " of /sweep does not match the checksum written with it (changed or damaged since); the "
                          "file is left as it is: remove it and run again without --resume");
}

std::int64_t SweepPartialFile::event_position(std::int64_t rows_needed) {
  const std::int64_t last = static_cast<std::int64_t>(block_capacity_.size()) - 1;
  if (last >= 0 && block_used_ + rows_needed <= block_capacity_.back()) {
    const std::int64_t position = (last << block_shift) | block_used_;
    block_used_ += rows_needed;
    return position;
  }
  // A new block, twice the last (at least what this chunk needs); created and flushed before use.
  const std::int64_t capacity =
      std::max(rows_needed, block_capacity_.empty() ? first_block_rows : 2 * block_capacity_.back());
  auto fail_fn = [this](const std::string& what) { fail(what); };
  const SweepHdf5 h5(fail_fn);
  const std::int64_t k = last + 1;
  h5.create_allocated(file_.get(), "/partial/events_" + std::to_string(k), H5T_IEEE_F64LE, capacity,
                      event_row_width, nullptr);
  if (H5Fflush(file_.get(), H5F_SCOPE_LOCAL) < 0) fail("cannot flush");
  block_capacity_.push_back(capacity);
  block_used_ = rows_needed;
  return k << block_shift;
}

void SweepPartialFile::write(const SweepChunk& c) {
  const hdf5::QuietHdf5Errors quiet;
  auto fail_fn = [this](const std::string& what) { fail(what); };
  const SweepHdf5 h5(fail_fn);
  Handle sweep(H5Gopen2(file_.get(), "/sweep", H5P_DEFAULT), H5Gclose);
  const auto rows = c.rows;
  // Crossings, then the rows, then (after a flush) the status that marks them complete.
  const std::int64_t crossings = static_cast<std::int64_t>(c.events.size()) / event_row_width;
  std::vector<std::int64_t> event_first(static_cast<std::size_t>(rows), -1);
  if (crossings > 0) {
    const std::int64_t position = event_position(crossings);
    const std::int64_t block = position >> block_shift, offset = position & ((std::int64_t{1} << block_shift) - 1);
    h5.write_rows(file_.get(), "/partial/events_" + std::to_string(block), H5T_NATIVE_DOUBLE, offset, crossings,
                  event_row_width, c.events.data());
    std::int64_t cursor = position;
    for (std::int64_t r = 0; r < rows; ++r) {
      event_first[static_cast<std::size_t>(r)] = cursor;
      cursor += c.event_count[static_cast<std::size_t>(r)] + c.sample_count[static_cast<std::size_t>(r)];
    }
  }
  std::vector<std::int64_t> index(static_cast<std::size_t>(rows));
  for (std::int64_t r = 0; r < rows; ++r) index[static_cast<std::size_t>(r)] = c.first + r;
  h5.write_rows(sweep.get(), "index", H5T_NATIVE_INT64, c.first, rows, 1, index.data());
  std::size_t offset = 0;
  int width = 0;
  for (const auto& in : layout_.inputs) width += in.width;
  std::vector<double> column(static_cast<std::size_t>(rows) * 4);
  for (const auto& in : layout_.inputs) {
    column.resize(static_cast<std::size_t>(rows * in.width));
    for (std::int64_t r = 0; r < rows; ++r)
      for (int k = 0; k < in.width; ++k)
        column[static_cast<std::size_t>(r * in.width + k)] = c.inputs[static_cast<std::size_t>(r * width) + offset + static_cast<std::size_t>(k)];
    h5.write_rows(sweep.get(), in.name, H5T_NATIVE_DOUBLE, c.first, rows, in.width, column.data());
    offset += static_cast<std::size_t>(in.width);
  }
  h5.write_rows(sweep.get(), "steps", H5T_NATIVE_INT64, c.first, rows, 1, c.steps.data());
  h5.write_rows(sweep.get(), "rejected_steps", H5T_NATIVE_INT64, c.first, rows, 1, c.rejected_steps.data());
  h5.write_rows(sweep.get(), "event_count", H5T_NATIVE_INT64, c.first, rows, 1, c.event_count.data());
  h5.write_rows(sweep.get(), "sample_count", H5T_NATIVE_INT64, c.first, rows, 1, c.sample_count.data());
  h5.write_rows(sweep.get(), "event_first", H5T_NATIVE_INT64, c.first, rows, 1, event_first.data());
  h5.write_rows(sweep.get(), "cpu_seconds", H5T_NATIVE_DOUBLE, c.first, rows, 1, c.cpu_seconds.data());
  h5.write_rows(sweep.get(), "t_final", H5T_NATIVE_DOUBLE, c.first, rows, 1, c.t_final.data());
  h5.write_rows(sweep.get(), "angular_momentum", H5T_NATIVE_DOUBLE, c.first, rows, 3, c.angular_momentum.data());
  h5.write_rows(sweep.get(), "orientation", H5T_NATIVE_DOUBLE, c.first, rows, 4, c.orientation.data());
  h5.write_rows(sweep.get(), "gamma", H5T_NATIVE_DOUBLE, c.first, rows, 3, c.gamma.data());
  const auto errors = layout_.error_names.size();
  column.resize(static_cast<std::size_t>(rows));
  for (std::size_t e = 0; e < errors; ++e) {
    for (std::int64_t r = 0; r < rows; ++r) column[static_cast<std::size_t>(r)] = c.max_errors[static_cast<std::size_t>(r) * errors + e];
    h5.write_rows(sweep.get(), error_column(layout_.error_names[e]), H5T_NATIVE_DOUBLE, c.first, rows, 1, column.data());
  }
  // Reasons only for a chunk that has one (unwritten rows read as empty strings).
  if (std::any_of(c.reasons.begin(), c.reasons.end(), [](const std::string& s) { return !s.empty(); })) {
    std::vector<char> reasons(static_cast<std::size_t>(rows) * reason_width, '\0');
    for (std::int64_t r = 0; r < rows; ++r) {
      const std::string& s = c.reasons[static_cast<std::size_t>(r)];
      std::memcpy(reasons.data() + static_cast<std::size_t>(r) * reason_width, s.data(),
                  std::min(s.size(), reason_width));
    }
    Handle reason_type = fixed_string_type(reason_width);
    h5.write_rows(sweep.get(), "reason", reason_type.get(), c.first, rows, 1, reasons.data());
  }
  const std::vector<std::uint64_t> hashes = sweep_chunk_hashes(c, layout_, event_first);
  h5.write_rows(file_.get(), "/partial/row_hash", H5T_NATIVE_UINT64, c.first, rows, 1, hashes.data());
  if (H5Fflush(file_.get(), H5F_SCOPE_LOCAL) < 0) fail("cannot flush");
  h5.write_rows(sweep.get(), "status", H5T_NATIVE_INT64, c.first, rows, 1, c.status.data());
  if (H5Fflush(file_.get(), H5F_SCOPE_LOCAL) < 0) fail("cannot flush");
  for (std::int64_t r = 0; r < rows; ++r) {
    done_[static_cast<std::size_t>(c.first + r)] = 1;
    if (c.status[static_cast<std::size_t>(r)] != 0) ++failures_;
  }
}

void SweepPartialFile::close() { file_.reset(); }

}  // namespace lgi::experiments

// The final file of `lgi sweep`, written from the partial one
// (sweep_file.hpp): /sweep in index order, /events sorted by trajectory
// index (and in time within a trajectory), /parameters and /provenance.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>

#include "experiments/io/h5md_writer.hpp"  // OutputFileError
#include "experiments/io/sweep_file.hpp"
#include "experiments/io/sweep_hdf5.hpp"

namespace lgi::experiments {

using hdf5::Handle;
using namespace sweep_hdf5;

namespace {

/// /events (crossings: with the event and direction columns) or /trajectory
/// (samples) columns, appended in batches to extendible chunked datasets.
class EventColumns {
 public:
  /// `rows`: how many rows there will be (the chunks are no longer than that, at most 16384).
  EventColumns(hid_t group, bool crossings, std::int64_t rows, const hdf5::Fail& fail)
      : group_(group), crossings_(crossings), chunk_rows_(static_cast<hsize_t>(std::clamp<std::int64_t>(rows, 1, 16384))),
        fail_(fail) {
    create("index", H5T_STD_I64LE, 1);
    if (crossings_) {
      create("event", H5T_STD_I32LE, 1);
      create("direction", H5T_STD_I32LE, 1);
    }
    create("step", H5T_STD_I64LE, 1);
    create("t", H5T_IEEE_F64LE, 1);
    create("angular_momentum", H5T_IEEE_F64LE, 3);
    create("orientation", H5T_IEEE_F64LE, 4);
    create("gamma", H5T_IEEE_F64LE, 3);
  }
  /// Partial-file rows (event_row_width values each).
  void append(const std::vector<double>& rows) {
    const auto n = static_cast<std::int64_t>(rows.size()) / event_row_width;
    if (n == 0) return;
    std::vector<std::int64_t> i64(static_cast<std::size_t>(n));
    std::vector<std::int32_t> i32(static_cast<std::size_t>(n));
    std::vector<double> f(static_cast<std::size_t>(n) * 4);
    auto ints64 = [&](int col, const char* name) {
      for (std::int64_t r = 0; r < n; ++r) i64[static_cast<std::size_t>(r)] = static_cast<std::int64_t>(at(rows, r, col));
      put(name, H5T_NATIVE_INT64, n, 1, i64.data());
    };
    auto ints32 = [&](int col, const char* name) {
      for (std::int64_t r = 0; r < n; ++r) i32[static_cast<std::size_t>(r)] = static_cast<std::int32_t>(at(rows, r, col));
      put(name, H5T_NATIVE_INT32, n, 1, i32.data());
    };
    auto reals = [&](int col, int width, const char* name) {
      f.resize(static_cast<std::size_t>(n * width));
      for (std::int64_t r = 0; r < n; ++r)
        for (int k = 0; k < width; ++k) f[static_cast<std::size_t>(r * width + k)] = at(rows, r, col + k);
      put(name, H5T_NATIVE_DOUBLE, n, width, f.data());
    };
    ints64(0, "index");
    if (crossings_) {
      ints32(1, "event");
      ints32(2, "direction");
    }
    ints64(3, "step");
    reals(4, 1, "t");
    reals(5, 3, "angular_momentum");
    reals(8, 4, "orientation");
    reals(12, 3, "gamma");
    rows_ += n;
  }

 private:
  static double at(const std::vector<double>& rows, std::int64_t r, int col) {
    return rows[static_cast<std::size_t>(r * event_row_width + col)];
  }
  void create(const char* name, hid_t type, int width) {
    Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    H5Pset_obj_track_times(dcpl.get(), false);
    const hsize_t chunk[2] = {chunk_rows_, static_cast<hsize_t>(width)};
    H5Pset_chunk(dcpl.get(), width > 1 ? 2 : 1, chunk);
    const hsize_t dims[2] = {0, static_cast<hsize_t>(width)}, max[2] = {H5S_UNLIMITED, static_cast<hsize_t>(width)};
    Handle s(H5Screate_simple(width > 1 ? 2 : 1, dims, max), H5Sclose);
    Handle d(H5Dcreate2(group_, name, type, s.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT), H5Dclose);
    if (!d.valid()) fail_(std::string("cannot create /events/") + name);
  }
  void put(const char* name, hid_t memory_type, std::int64_t n, int width, const void* data) {
    Handle d(H5Dopen2(group_, name, H5P_DEFAULT), H5Dclose);
    const hsize_t dims[2] = {static_cast<hsize_t>(rows_ + n), static_cast<hsize_t>(width)};
    if (!d.valid() || H5Dset_extent(d.get(), dims) < 0) fail_(std::string("cannot extend /events/") + name);
    Handle file_space = row_selection(d.get(), rows_, n, width);
    Handle memory = space(n, width);
    if (H5Dwrite(d.get(), memory_type, memory.get(), file_space.get(), H5P_DEFAULT, data) < 0)
      fail_(std::string("cannot write /events/") + name);
  }
  hid_t group_;
  bool crossings_;
  hsize_t chunk_rows_;
  const hdf5::Fail& fail_;
  std::int64_t rows_ = 0;
};

/// The partial file's crossing and sample rows, trajectory by trajectory
/// (index order), into /events and /trajectory; returns each trajectory's
/// first row in both.
struct RowOffsets {
  std::vector<std::int64_t> events, samples;
};
RowOffsets copy_event_rows(const SweepHdf5& in, const hdf5::Fail& fail_in, hid_t partial,
                           const std::vector<std::int64_t>& first, const std::vector<std::int64_t>& crossings,
                           const std::vector<std::int64_t>& samples, EventColumns& events, EventColumns* trajectory) {
  const auto n = static_cast<std::int64_t>(first.size());
  RowOffsets at{std::vector<std::int64_t>(first.size()), std::vector<std::int64_t>(first.size())};
  std::vector<double> batch, crossing_rows, sample_rows;
  std::int64_t next_event = 0, next_sample = 0;
  auto flush = [&] {
    crossing_rows.clear(), sample_rows.clear();
    for (std::size_t r = 0; r < batch.size(); r += event_row_width) {
      auto& to = batch[r + 1] == sample_row ? sample_rows : crossing_rows;
      to.insert(to.end(), batch.begin() + static_cast<std::ptrdiff_t>(r),
                batch.begin() + static_cast<std::ptrdiff_t>(r + event_row_width));
    }
    events.append(crossing_rows);
    if (trajectory) trajectory->append(sample_rows);
    batch.clear();
  };
  auto rows_of = [&](std::int64_t k) { return crossings[static_cast<std::size_t>(k)] + samples[static_cast<std::size_t>(k)]; };
  for (std::int64_t r = 0; r < n;) {
    // A run of trajectories whose rows are adjacent in one block: one read.
    const std::int64_t start = first[static_cast<std::size_t>(r)];
    std::int64_t end = r + 1, total = rows_of(r);
    while (end < n && first[static_cast<std::size_t>(end)] == start + total &&
           (first[static_cast<std::size_t>(end)] >> block_shift) == (start >> block_shift))
      total += rows_of(end++);
    for (std::int64_t k = r; k < end; ++k) {
      at.events[static_cast<std::size_t>(k)] = next_event;
      at.samples[static_cast<std::size_t>(k)] = next_sample;
      next_event += crossings[static_cast<std::size_t>(k)];
      next_sample += samples[static_cast<std::size_t>(k)];
    }
    if (total > 0) {
      const std::size_t old = batch.size();
      batch.resize(old + static_cast<std::size_t>(total * event_row_width));
      in.read_rows(partial, "/partial/events_" + std::to_string(start >> block_shift), H5T_NATIVE_DOUBLE,
                   start & ((std::int64_t{1} << block_shift) - 1), total, event_row_width, batch.data() + old);
      // The integer columns (index, event, direction, step) as the run wrote them:
      // a damaged partial file must be reported, not reach EventColumns' integer casts.
      for (std::size_t q = old; q < batch.size(); q += event_row_width)
        for (int col = 0; col < 4; ++col) {
          const double v = batch[q + static_cast<std::size_t>(col)];
          const double bound = col == 1 || col == 2 ? 2147483647.0 : 9.0e18;
          if (!(std::abs(v) <= bound && v == std::floor(v)))
            fail_in("/partial/events_" + std::to_string(start >> block_shift) +
                    ": a crossing row whose index, event, direction or step is not an integer in range");
        }
      if (batch.size() >= static_cast<std::size_t>(65536 * event_row_width)) flush();
    }
    r = end;
  }
  flush();
  return at;
}

void write_text_attributes(hid_t loc, const std::vector<std::pair<std::string, std::string>>& text,
                           const hdf5::Fail& fail) {
  for (const auto& [k, v] : text) hdf5::write_vlen_string(loc, k.c_str(), v, false, fail);
}

/// /sweep/reason of the final file: fixed-length text as wide as the longest
/// reason (so h5py compares rows as bytes). Only failed rows have one: those
/// are read, in runs of consecutive rows.
void write_reasons(const SweepHdf5& in, const SweepHdf5& out, hid_t src, hid_t dst, std::int64_t n) {
  std::vector<std::int64_t> status(static_cast<std::size_t>(n));
  in.read_rows(src, "status", H5T_NATIVE_INT64, 0, n, 1, status.data());
  std::vector<std::string> reasons(static_cast<std::size_t>(n));
  std::size_t longest = 1;
  {
    Handle t = fixed_string_type(reason_width);
    std::vector<char> text;
    for (std::int64_t r = 0; r < n;) {
      if (status[static_cast<std::size_t>(r)] == 0) {
        ++r;
        continue;
      }
      std::int64_t end = r;
      while (end < n && status[static_cast<std::size_t>(end)] != 0) ++end;
      text.assign(static_cast<std::size_t>(end - r) * reason_width, '\0');
      in.read_rows(src, "reason", t.get(), r, end - r, 1, text.data());
      for (std::int64_t k = r; k < end; ++k) {
        const char* p = text.data() + static_cast<std::size_t>(k - r) * reason_width;
        reasons[static_cast<std::size_t>(k)].assign(p, ::strnlen(p, reason_width));
        longest = std::max(longest, reasons[static_cast<std::size_t>(k)].size());
      }
      r = end;
    }
  }
  {
    std::vector<char> narrow(static_cast<std::size_t>(n) * longest, '\0');
    for (std::int64_t r = 0; r < n; ++r) {
      const std::string& text = reasons[static_cast<std::size_t>(r)];
      std::memcpy(narrow.data() + static_cast<std::size_t>(r) * longest, text.data(), text.size());
    }
    Handle t = fixed_string_type(longest);
    out.write_whole(dst, "reason", t.get(), t.get(), n, 1, narrow.data());
  }

}

}  // namespace

void SweepPartialFile::write_final(const std::string& path, const SweepAttributes& attributes) {
  const auto start = std::chrono::steady_clock::now();
  const hdf5::QuietHdf5Errors quiet;
  auto fail_in = [this](const std::string& what) { fail(what); };
  auto fail_out = [this, &path](const std::string& what) {  // a failed write (exit 1): the .partial is kept
    throw OutputWriteError(path + ": " + what + " (" + hdf5::hdf5_error_detail() + "); " + path_ +
                           " is kept (free space and finish it with --resume)");
  };
  const SweepHdf5 in(fail_in), out(fail_out);
  Handle file = hdf5::create_file(path, fail_out);
  Handle src(H5Gopen2(file_.get(), "/sweep", H5P_DEFAULT), H5Gclose);
  Handle dst = hdf5::create_group(file.get(), "/sweep", fail_out);
  const std::int64_t n = layout_.count;
  std::vector<double> real;
  std::vector<std::int64_t> integer;
  auto copy = [&](const std::string& name, int width, bool is_integer) {
    const auto size = static_cast<std::size_t>(n * width);
    if (is_integer) {
      integer.resize(size);
      in.read_rows(src.get(), name, H5T_NATIVE_INT64, 0, n, width, integer.data());
      out.write_whole(dst.get(), name, H5T_STD_I64LE, H5T_NATIVE_INT64, n, width, integer.data());
    } else {
      real.resize(size);
      in.read_rows(src.get(), name, H5T_NATIVE_DOUBLE, 0, n, width, real.data());
      out.write_whole(dst.get(), name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, n, width, real.data());
    }
  };
  copy("index", 1, true);
  for (const auto& c : layout_.inputs) copy(c.name, c.width, false);
  for (const auto& c : fixed_columns) copy(c.name, c.width, c.integer);
  for (const auto& e : layout_.error_names) copy(error_column(e), 1, false);

  write_reasons(in, out, src.get(), dst.get(), n);

  // /events and /trajectory in index order; event_first and sample_first become rows there.
  std::vector<std::int64_t> first(static_cast<std::size_t>(n)), crossings(static_cast<std::size_t>(n)),
      samples(static_cast<std::size_t>(n));
  in.read_rows(src.get(), "event_first", H5T_NATIVE_INT64, 0, n, 1, first.data());
  in.read_rows(src.get(), "event_count", H5T_NATIVE_INT64, 0, n, 1, crossings.data());
  in.read_rows(src.get(), "sample_count", H5T_NATIVE_INT64, 0, n, 1, samples.data());
  Handle events_group = hdf5::create_group(file.get(), "/events", fail_out);
  hdf5::write_fixed_strings(events_group.get(), "names",
                            layout_.event_names.empty() ? std::vector<std::string>{""} : layout_.event_names, false,
                            fail_out);
  std::int64_t crossing_rows = 0, sample_rows = 0;
  for (std::size_t i = 0; i < crossings.size(); ++i) {  // only to size the chunks: no more than 16384 matters
    crossing_rows = std::min<std::int64_t>(crossing_rows + crossings[i], 16384);
    sample_rows = std::min<std::int64_t>(sample_rows + samples[i], 16384);
  }
  EventColumns events(events_group.get(), true, crossing_rows, fail_out);
  Handle trajectory_group;
  std::unique_ptr<EventColumns> trajectory;
  if (layout_.trajectories) {
    trajectory_group = hdf5::create_group(file.get(), "/trajectory", fail_out);
    trajectory = std::make_unique<EventColumns>(trajectory_group.get(), false, sample_rows, fail_out);
  }
  const RowOffsets at = copy_event_rows(in, fail_in, file_.get(), first, crossings, samples, events, trajectory.get());
  out.write_whole(dst.get(), "event_first", H5T_STD_I64LE, H5T_NATIVE_INT64, n, 1, at.events.data());
  if (layout_.trajectories)
    out.write_whole(dst.get(), "sample_first", H5T_STD_I64LE, H5T_NATIVE_INT64, n, 1, at.samples.data());

  Handle parameters = hdf5::create_group(file.get(), "/parameters", fail_out);
  write_text_attributes(parameters.get(), attributes.parameters, fail_out);
  for (const auto& [k, v] : attributes.numbers) hdf5::write_double_attribute(parameters.get(), k.c_str(), v, fail_out);
  Handle provenance = hdf5::create_group(file.get(), "/provenance", fail_out);
  write_text_attributes(provenance.get(), attributes.provenance, fail_out);
  // The cost of this file (the scaling model of scripts/plots/sweep_scaling.py uses it).
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  hdf5::write_vlen_string(provenance.get(), "final_write_seconds", hdf5::csv_number(seconds), false, fail_out);
  if (file.reset() < 0) fail_out("cannot close");
}

}  // namespace lgi::experiments

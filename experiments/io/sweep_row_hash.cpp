// Checksums of the finished rows of a partial sweep (sweep_row_hash.hpp).
#include "experiments/io/sweep_row_hash.hpp"

#include <algorithm>
#include <array>
#include <cstring>

#include "experiments/io/fnv_hash.hpp"

namespace lgi::experiments {

using namespace sweep_hdf5;

std::uint64_t sweep_row_hash(const SweepRowValues& r) {
  Fnv1a h;
  h.value(r.index);
  h.values(r.inputs, r.input_values);
  for (const std::int64_t k : {r.status, r.steps, r.rejected_steps, r.event_count, r.sample_count}) h.value(k);
  h.value(r.cpu_seconds);
  h.value(r.t_final);
  h.values(r.angular_momentum, 3);
  h.values(r.orientation, 4);
  h.values(r.gamma, 3);
  h.values(r.errors, r.error_values);
  h.value(r.event_first);
  if (r.status != 0) h.bytes(r.reason, reason_width);  // the final file reads a reason only for these
  h.values(r.events, static_cast<std::size_t>(r.event_count + r.sample_count) * event_row_width);
  return h.get();
}

std::vector<std::uint64_t> sweep_chunk_hashes(const SweepChunk& c, const SweepLayout& layout,
                                              const std::vector<std::int64_t>& event_first) {
  std::size_t width = 0;
  for (const auto& in : layout.inputs) width += static_cast<std::size_t>(in.width);
  const std::size_t errors = layout.error_names.size();
  std::vector<std::uint64_t> hashes(static_cast<std::size_t>(c.rows));
  std::array<char, reason_width> reason{};
  std::size_t event_at = 0;
  for (std::size_t r = 0; r < hashes.size(); ++r) {
    SweepRowValues v;
    v.index = c.first + static_cast<std::int64_t>(r);
    v.status = c.status[r], v.steps = c.steps[r], v.rejected_steps = c.rejected_steps[r];
    v.event_count = c.event_count[r], v.sample_count = c.sample_count[r], v.event_first = event_first[r];
    v.cpu_seconds = c.cpu_seconds[r], v.t_final = c.t_final[r];
    v.inputs = c.inputs.data() + r * width, v.input_values = width;
    v.angular_momentum = c.angular_momentum.data() + 3 * r;
    v.orientation = c.orientation.data() + 4 * r;
    v.gamma = c.gamma.data() + 3 * r;
    v.errors = c.max_errors.data() + r * errors, v.error_values = errors;
    // As stored: a chunk whose reasons are all empty writes none, and unwritten rows read as zeros.
    reason.fill('\0');
    std::memcpy(reason.data(), c.reasons[r].data(), std::min(c.reasons[r].size(), reason_width));
    v.reason = reason.data();
    v.events = c.events.data() + event_at;
    event_at += static_cast<std::size_t>(v.event_count + v.sample_count) * event_row_width;
    hashes[r] = sweep_row_hash(v);
  }
  return hashes;
}

namespace {

constexpr std::int64_t block_rows = 4096;  // rows read back at a time

/// The rows a..a+n−1 of one /sweep column of `width` values per row.
std::vector<double> read_reals(const SweepHdf5& h5, hid_t sweep, const std::string& name, std::int64_t a,
                               std::int64_t n, int width) {
  std::vector<double> v(static_cast<std::size_t>(n * width));
  h5.read_rows(sweep, name, H5T_NATIVE_DOUBLE, a, n, width, v.data());
  return v;
}

std::vector<std::int64_t> read_ints(const SweepHdf5& h5, hid_t sweep, const std::string& name, std::int64_t a,
                                    std::int64_t n) {
  std::vector<std::int64_t> v(static_cast<std::size_t>(n));
  h5.read_rows(sweep, name, H5T_NATIVE_INT64, a, n, 1, v.data());
  return v;
}

/// The crossings and samples of the finished rows a..a+n−1, each row's
/// starting at its offset in the returned vector (runs of rows adjacent in
/// one block are read at once, as the final file does).
std::vector<double> read_row_events(const SweepHdf5& h5, hid_t file, std::int64_t a, std::int64_t n,
                                    const std::vector<std::int64_t>& status, const std::vector<std::int64_t>& first,
                                    const std::vector<std::int64_t>& rows_of, std::vector<std::size_t>& offset) {
  std::vector<double> events;
  offset.assign(static_cast<std::size_t>(n), 0);
  auto row = [](std::int64_t i) { return static_cast<std::size_t>(i); };
  for (std::int64_t i = a; i < a + n;) {
    if (status[row(i)] < 0 || rows_of[row(i)] == 0) {
      offset[row(i - a)] = events.size();
      ++i;
      continue;
    }
    const std::int64_t start = first[row(i)];
    std::int64_t end = i + 1, total = rows_of[row(i)];
    while (end < a + n && status[row(end)] >= 0 && rows_of[row(end)] > 0 && first[row(end)] == start + total &&
           (first[row(end)] >> block_shift) == (start >> block_shift))
      total += rows_of[row(end++)];
    std::size_t at = events.size();
    for (std::int64_t k = i; k < end; ++k) {
      offset[row(k - a)] = at;
      at += static_cast<std::size_t>(rows_of[row(k)] * event_row_width);
    }
    const std::size_t old = events.size();
    events.resize(old + static_cast<std::size_t>(total * event_row_width));
    h5.read_rows(file, "/partial/events_" + std::to_string(start >> block_shift), H5T_NATIVE_DOUBLE,
                 start & ((std::int64_t{1} << block_shift) - 1), total, event_row_width, events.data() + old);
    i = end;
  }
  return events;
}

}  // namespace

std::int64_t first_damaged_sweep_row(const SweepHdf5& h5, hid_t file, const SweepLayout& layout,
                                     const std::vector<std::int64_t>& status, const std::vector<std::int64_t>& first,
                                     const std::vector<std::int64_t>& crossings,
                                     const std::vector<std::int64_t>& samples) {
  hdf5::Handle sweep(H5Gopen2(file, "/sweep", H5P_DEFAULT), H5Gclose);
  const std::int64_t n = layout.count;
  std::vector<std::int64_t> rows_of(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < rows_of.size(); ++i) rows_of[i] = crossings[i] + samples[i];
  std::size_t width = 0;
  for (const auto& in : layout.inputs) width += static_cast<std::size_t>(in.width);
  const std::size_t errors = layout.error_names.size();
  const hdf5::Handle reason_type = fixed_string_type(reason_width);
  std::vector<double> inputs(width), row_errors(errors);
  std::vector<std::size_t> event_offset;
  for (std::int64_t a = 0; a < n; a += block_rows) {
    const std::int64_t m = std::min(block_rows, n - a);
    if (std::none_of(status.begin() + a, status.begin() + a + m, [](std::int64_t s) { return s >= 0; })) continue;
    const auto index = read_ints(h5, sweep.get(), "index", a, m), steps = read_ints(h5, sweep.get(), "steps", a, m),
               rejected = read_ints(h5, sweep.get(), "rejected_steps", a, m);
    std::vector<std::vector<double>> input_columns, error_columns;
    for (const auto& in : layout.inputs) input_columns.push_back(read_reals(h5, sweep.get(), in.name, a, m, in.width));
    for (const auto& e : layout.error_names) error_columns.push_back(read_reals(h5, sweep.get(), error_column(e), a, m, 1));
    const auto cpu = read_reals(h5, sweep.get(), "cpu_seconds", a, m, 1), t_final = read_reals(h5, sweep.get(), "t_final", a, m, 1),
               momentum = read_reals(h5, sweep.get(), "angular_momentum", a, m, 3),
               orientation = read_reals(h5, sweep.get(), "orientation", a, m, 4),
               gamma = read_reals(h5, sweep.get(), "gamma", a, m, 3);
    std::vector<char> reasons(static_cast<std::size_t>(m) * reason_width);
    h5.read_rows(sweep.get(), "reason", reason_type.get(), a, m, 1, reasons.data());
    std::vector<std::uint64_t> stored(static_cast<std::size_t>(m));
    h5.read_rows(file, "/partial/row_hash", H5T_NATIVE_UINT64, a, m, 1, stored.data());
    const std::vector<double> events = read_row_events(h5, file, a, m, status, first, rows_of, event_offset);
    for (std::int64_t k = 0; k < m; ++k) {
      const auto i = static_cast<std::size_t>(a + k), r = static_cast<std::size_t>(k);
      if (status[i] < 0) continue;
      std::size_t at = 0;
      for (std::size_t c = 0; c < input_columns.size(); ++c) {
        const auto w = static_cast<std::size_t>(layout.inputs[c].width);
        std::copy_n(input_columns[c].begin() + static_cast<std::ptrdiff_t>(r * w), w, inputs.begin() + static_cast<std::ptrdiff_t>(at));
        at += w;
      }
      for (std::size_t e = 0; e < errors; ++e) row_errors[e] = error_columns[e][r];
      SweepRowValues v;
      v.index = index[r], v.status = status[i], v.steps = steps[r], v.rejected_steps = rejected[r];
      v.event_count = crossings[i], v.sample_count = samples[i], v.event_first = first[i];
      v.cpu_seconds = cpu[r], v.t_final = t_final[r];
      v.inputs = inputs.data(), v.input_values = width;
      v.angular_momentum = momentum.data() + 3 * r, v.orientation = orientation.data() + 4 * r;
      v.gamma = gamma.data() + 3 * r;
      v.errors = row_errors.data(), v.error_values = errors;
      v.reason = reasons.data() + r * reason_width;
      v.events = events.data() + event_offset[r];
      if (sweep_row_hash(v) != stored[r]) return a + k;
    }
  }
  return -1;
}

}  // namespace lgi::experiments

#pragma once
// The checksum of a finished row of a partial sweep file (sweep_file.hpp;
// experiments/SWEEPS.md, "Resuming"). Each finished row i has in
// /partial/row_hash[i] the FNV-1a hash (fnv_hash.hpp) of every value the
// final file takes from it: index, the inputs, the fixed columns (status
// included), the invariant errors, event_first, the reason of a failed row
// (its reason_width stored bytes) and the row's crossings and samples. It is
// written with the row, before the status that marks the row finished.
// --resume checks every finished row against it before going on, and refuses
// the file, naming the first row that does not match: a bit flipped in a row,
// or a status set by hand on a row that was never computed.
//
// Per row rather than per chunk: a resumed run cuts the pending rows into
// chunks of its own, so only a row is the same unit in every run of a sweep.
#include <cstdint>
#include <vector>

#include "experiments/io/sweep_file.hpp"
#include "experiments/io/sweep_hdf5.hpp"

namespace lgi::experiments {

/// One row's stored values, wherever they are held (a chunk being written, or
/// blocks read back from the file). Arrays of `n` values: inputs (every
/// input column's values in layout order), errors, events.
struct SweepRowValues {
  std::int64_t index = 0, status = 0, steps = 0, rejected_steps = 0, event_count = 0, sample_count = 0,
               event_first = -1;
  double cpu_seconds = 0.0, t_final = 0.0;
  const double *inputs = nullptr, *angular_momentum = nullptr, *orientation = nullptr, *gamma = nullptr,
               *errors = nullptr, *events = nullptr;
  std::size_t input_values = 0, error_values = 0;
  const char* reason = nullptr;  // sweep_hdf5::reason_width bytes (read only if status != 0)
};

std::uint64_t sweep_row_hash(const SweepRowValues& row);

/// The hash of each row of a chunk as SweepPartialFile::write stores it.
std::vector<std::uint64_t> sweep_chunk_hashes(const SweepChunk& chunk, const SweepLayout& layout,
                                              const std::vector<std::int64_t>& event_first);

/// The first finished row (status ≥ 0) of the partial file's /sweep whose
/// values do not match /partial/row_hash; −1 if every one does. Reads the
/// file in blocks of rows (bounded memory). `status`, `first`, `crossings`,
/// `samples`: those columns, already read and checked for range.
std::int64_t first_damaged_sweep_row(const sweep_hdf5::SweepHdf5& h5, hid_t file, const SweepLayout& layout,
                                     const std::vector<std::int64_t>& status, const std::vector<std::int64_t>& first,
                                     const std::vector<std::int64_t>& crossings,
                                     const std::vector<std::int64_t>& samples);

}  // namespace lgi::experiments

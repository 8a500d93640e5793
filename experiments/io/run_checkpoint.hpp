#pragma once
// The checkpoint of a long run, as a resumed run needs it (lgi long-time
// --resume; RESULTS.md, "long-time --resume"): the loop's checkpoint
// (integrators/core/run_config.hpp, LoopCheckpoint) and what the command adds
// (rows written, CPU and output time so far, the running error maxima).
//
// In the file it is a record of two slots of slot_bytes each (results_file.hpp,
// create_record), written in turn: a kill while one is written leaves the
// other intact. A slot is
//   magic "lgickpt1", sequence (uint64, > 0), payload length, FNV-1a 64-bit
//   hash of the payload (uint64 each), then the payload: 8-byte
//   little-endian numbers (int64 or float64): rows, step, t, h, the state
//   (integrators/core/state_space.hpp: on SO(3) × ℝ³ R, 9, column by column, then
//   Π, 3; on T³ × ℝ³ the angles q, 3, then the momenta p, 3), the 4 work
//   counters, cpu_seconds, output_seconds, n, window_max (n), run_max (n), m,
//   the scheme's memory (m). A slot of one state space never decodes as the
//   other's: its length does not fit.
// A slot whose magic, length or hash is wrong is empty (never half read).
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "integrators/core/run_config.hpp"

namespace lgi::experiments {

/// On states S (integrators/core/state_space.hpp).
template <class S>
struct BasicRunCheckpoint {
  std::int64_t rows = 0;  // table rows written up to this checkpoint
  integrators::BasicLoopCheckpoint<S> loop;
  double cpu_seconds = 0.0, output_seconds = 0.0;  // the run's so far
  std::vector<double> window_max, run_max;          // one per error column
};

using RunCheckpoint = BasicRunCheckpoint<system::State>;              // SO(3) × ℝ³
using TorusRunCheckpoint = BasicRunCheckpoint<system::TorusState>;    // T³ × ℝ³ (the Cardan top)

inline constexpr std::size_t checkpoint_slot_bytes = 4096;

/// One slot (checkpoint_slot_bytes). std::length_error if the checkpoint
/// does not fit (a scheme's memory of hundreds of numbers).
template <class S>
std::vector<unsigned char> encode_checkpoint(const BasicRunCheckpoint<S>& c, std::uint64_t sequence);

/// The checkpoint in a slot and its sequence number; std::nullopt if the
/// slot is empty, torn, corrupted, or holds other than `error_columns` maxima.
template <class S = system::State>
std::optional<std::pair<BasicRunCheckpoint<S>, std::uint64_t>> decode_checkpoint(std::span<const unsigned char> slot,
                                                                                 std::size_t error_columns);

/// The newest checkpoint of a record of slots with at most `max_rows` rows
/// (std::nullopt if there is none), and the sequence number the next
/// checkpoint takes: above every intact slot's.
template <class S = system::State>
std::optional<BasicRunCheckpoint<S>> newest_checkpoint(std::span<const unsigned char> record,
                                                       std::size_t error_columns, std::int64_t max_rows,
                                                       std::uint64_t& next_sequence);

}  // namespace lgi::experiments

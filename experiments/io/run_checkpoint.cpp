// Checkpoint slots (run_checkpoint.hpp). The bytes decoded here come from a
// file that may be torn or damaged: every length and count is checked before
// it is used (fuzz/fuzz_h5_readers.cpp).
#include "experiments/io/run_checkpoint.hpp"

#include "experiments/io/fnv_hash.hpp"

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace lgi::experiments {
namespace {

static_assert(std::endian::native == std::endian::little, "checkpoint slots are little-endian as stored");

constexpr char magic[8] = {'l', 'g', 'i', 'c', 'k', 'p', 't', '1'};
constexpr std::size_t header_bytes = 32;

/// The slot's hash covers its sequence number and length as well as the
/// payload, so a damaged header byte is caught like a damaged payload byte.
std::uint64_t slot_hash(std::uint64_t sequence, std::uint64_t length, std::span<const unsigned char> payload) {
  Fnv1a h;
  h.value(sequence);
  h.value(length);
  h.bytes(payload);
  return h.get();
}

class Writer {
 public:
  template <class T>
  void put(T x) {
    static_assert(sizeof(T) == 8);
    unsigned char b[8];
    std::memcpy(b, &x, 8);
    bytes.insert(bytes.end(), b, b + 8);
  }
  void put_all(std::span<const double> xs) {
    put(static_cast<std::int64_t>(xs.size()));
    for (double x : xs) put(x);
  }
  std::vector<unsigned char> bytes;
};

class CheckpointBytes {
 public:
  explicit CheckpointBytes(std::span<const unsigned char> b) : b_(b) {}
  template <class T>
  bool get(T& x) {
    static_assert(sizeof(T) == 8);
    if (b_.size() - at_ < 8) return false;
    std::memcpy(&x, b_.data() + at_, 8);
    at_ += 8;
    return true;
  }
  /// A count, then that many numbers (at most what is left).
  bool get_all(std::vector<double>& xs) {
    std::int64_t n = 0;
    if (!get(n) || n < 0 || static_cast<std::uint64_t>(n) > (b_.size() - at_) / 8) return false;
    xs.resize(static_cast<std::size_t>(n));
    for (double& x : xs) (void)get(x);
    return true;
  }
  bool end() const { return at_ == b_.size(); }

 private:
  std::span<const unsigned char> b_;
  std::size_t at_ = 0;
};

}  // namespace

template <class S>
std::vector<unsigned char> encode_checkpoint(const BasicRunCheckpoint<S>& c, std::uint64_t sequence) {
  using Space = integrators::StateSpace<S>;
  Writer p;
  const integrators::BasicLoopCheckpoint<S>& l = c.loop;
  p.put(c.rows);
  p.put(l.step);
  p.put(l.t);
  p.put(l.h);
  double state[Space::dimension];
  Space::write(l.state, state);
  for (double x : state) p.put(x);
  p.put(l.work.rhs_evaluations);
  p.put(l.work.rejected_steps);
  p.put(l.work.newton_iterations_max);
  p.put(l.work.newton_failures);
  p.put(c.cpu_seconds);
  p.put(c.output_seconds);
  p.put_all(c.window_max);
  for (double x : c.run_max) p.put(x);
  p.put_all(l.memory);
  if (c.run_max.size() != c.window_max.size()) throw std::invalid_argument("checkpoint: run_max and window_max differ");
  if (header_bytes + p.bytes.size() > checkpoint_slot_bytes) throw std::length_error("checkpoint: too large for a slot");
  Writer slot;
  slot.bytes.assign(magic, magic + 8);
  slot.put(sequence);
  slot.put(static_cast<std::uint64_t>(p.bytes.size()));
  slot.put(slot_hash(sequence, p.bytes.size(), p.bytes));
  // The payload copied into the padded slot: the same bytes as appending then
  // padding, without GCC 12's false -Wstringop-overflow on vector::insert.
  const auto payload_at = static_cast<std::ptrdiff_t>(slot.bytes.size());
  slot.bytes.resize(checkpoint_slot_bytes, 0);
  std::copy(p.bytes.begin(), p.bytes.end(), slot.bytes.begin() + payload_at);
  return slot.bytes;
}

template <class S>
std::optional<std::pair<BasicRunCheckpoint<S>, std::uint64_t>> decode_checkpoint(std::span<const unsigned char> slot,
                                                                                 std::size_t error_columns) {
  using Space = integrators::StateSpace<S>;
  if (slot.size() < header_bytes || std::memcmp(slot.data(), magic, 8) != 0) return std::nullopt;
  CheckpointBytes h(slot.subspan(8, 24));
  std::uint64_t sequence = 0, length = 0, hash = 0;
  (void)h.get(sequence);
  (void)h.get(length);
  (void)h.get(hash);
  if (sequence == 0 || length > slot.size() - header_bytes) return std::nullopt;
  const auto payload = slot.subspan(header_bytes, static_cast<std::size_t>(length));
  if (slot_hash(sequence, length, payload) != hash) return std::nullopt;
  BasicRunCheckpoint<S> c;
  integrators::BasicLoopCheckpoint<S>& l = c.loop;
  CheckpointBytes p(payload);
  bool ok = p.get(c.rows) && p.get(l.step) && p.get(l.t) && p.get(l.h);
  double state[Space::dimension] = {};
  for (std::size_t i = 0; i < Space::dimension && ok; ++i) ok = p.get(state[i]);
  Space::read(state, l.state);
  ok = ok && p.get(l.work.rhs_evaluations) && p.get(l.work.rejected_steps) && p.get(l.work.newton_iterations_max) &&
       p.get(l.work.newton_failures) && p.get(c.cpu_seconds) && p.get(c.output_seconds) && p.get_all(c.window_max);
  if (!ok || c.window_max.size() != error_columns) return std::nullopt;
  c.run_max.resize(error_columns);
  for (double& x : c.run_max) ok = ok && p.get(x);
  ok = ok && p.get_all(l.memory) && p.end();
  if (!ok || c.rows < 0 || l.step < 1) return std::nullopt;
  return std::pair{std::move(c), sequence};
}

template <class S>
std::optional<BasicRunCheckpoint<S>> newest_checkpoint(std::span<const unsigned char> record,
                                                       std::size_t error_columns, std::int64_t max_rows,
                                                       std::uint64_t& next_sequence) {
  std::optional<std::pair<BasicRunCheckpoint<S>, std::uint64_t>> best;
  next_sequence = 1;
  for (std::size_t at = 0; at + checkpoint_slot_bytes <= record.size(); at += checkpoint_slot_bytes) {
    auto c = decode_checkpoint<S>(record.subspan(at, checkpoint_slot_bytes), error_columns);
    if (c && c->second < UINT64_MAX) next_sequence = std::max(next_sequence, c->second + 1);
    if (c && c->first.rows <= max_rows && (!best || c->second > best->second)) best = std::move(c);
  }
  if (!best) return std::nullopt;
  return std::move(best->first);
}

// The two state spaces a long run is checkpointed on.
template std::vector<unsigned char> encode_checkpoint(const RunCheckpoint&, std::uint64_t);
template std::vector<unsigned char> encode_checkpoint(const TorusRunCheckpoint&, std::uint64_t);
template std::optional<std::pair<RunCheckpoint, std::uint64_t>> decode_checkpoint<system::State>(
    std::span<const unsigned char>, std::size_t);
template std::optional<std::pair<TorusRunCheckpoint, std::uint64_t>> decode_checkpoint<system::TorusState>(
    std::span<const unsigned char>, std::size_t);
template std::optional<RunCheckpoint> newest_checkpoint<system::State>(std::span<const unsigned char>, std::size_t,
                                                                      std::int64_t, std::uint64_t&);
template std::optional<TorusRunCheckpoint> newest_checkpoint<system::TorusState>(std::span<const unsigned char>,
                                                                                std::size_t, std::int64_t,
                                                                                std::uint64_t&);

}  // namespace lgi::experiments

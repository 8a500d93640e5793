// A SweepChunk as one byte buffer (sweep_ranks.hpp): the row counts, then
// each column as raw host-order values, then the reasons, each ended by '\0'.
// Both ends are the same build of lgi on the same kind of machine.
#include <cstring>
#include <stdexcept>

#include "experiments/commands/sweep/sweep_ranks.hpp"

namespace lgi::experiments {

namespace {

class Writer {
 public:
  template <class T>
  void value(const T& v) {
    const auto* p = reinterpret_cast<const char*>(&v);
    bytes.insert(bytes.end(), p, p + sizeof(T));
  }
  template <class T>
  void array(const std::vector<T>& v) {
    value(static_cast<std::uint64_t>(v.size()));
    const auto* p = reinterpret_cast<const char*>(v.data());
    bytes.insert(bytes.end(), p, p + v.size() * sizeof(T));
  }
  std::vector<char> bytes;
};

class Reader {
 public:
  explicit Reader(const std::vector<char>& b) : bytes_(b) {}
  template <class T>
  T value() {
    T v;
    take(&v, sizeof(T));
    return v;
  }
  template <class T>
  std::vector<T> array() {
    std::vector<T> v(static_cast<std::size_t>(value<std::uint64_t>()));
    take(v.data(), v.size() * sizeof(T));
    return v;
  }
  void take(void* out, std::size_t n) {
    if (at_ + n > bytes_.size()) throw std::runtime_error("a sweep chunk from another rank is truncated");
    std::memcpy(out, bytes_.data() + at_, n);
    at_ += n;
  }
  bool end() const { return at_ == bytes_.size(); }
  std::size_t at_ = 0;

 private:
  const std::vector<char>& bytes_;
};

}  // namespace

std::vector<char> pack_chunk(const SweepChunk& c) {
  Writer w;
  w.value(c.first), w.value(c.rows);
  w.array(c.status), w.array(c.steps), w.array(c.rejected_steps), w.array(c.event_count), w.array(c.sample_count);
  w.array(c.inputs), w.array(c.cpu_seconds), w.array(c.t_final), w.array(c.angular_momentum);
  w.array(c.orientation), w.array(c.gamma), w.array(c.max_errors), w.array(c.events);
  for (const auto& r : c.reasons) w.bytes.insert(w.bytes.end(), r.c_str(), r.c_str() + r.size() + 1);
  return std::move(w.bytes);
}

SweepChunk unpack_chunk(const std::vector<char>& bytes) {
  Reader r(bytes);
  SweepChunk c;
  c.first = r.value<std::int64_t>(), c.rows = r.value<std::int64_t>();
  c.status = r.array<std::int64_t>(), c.steps = r.array<std::int64_t>();
  c.rejected_steps = r.array<std::int64_t>(), c.event_count = r.array<std::int64_t>();
  c.sample_count = r.array<std::int64_t>();
  c.inputs = r.array<double>(), c.cpu_seconds = r.array<double>(), c.t_final = r.array<double>();
  c.angular_momentum = r.array<double>(), c.orientation = r.array<double>(), c.gamma = r.array<double>();
  c.max_errors = r.array<double>(), c.events = r.array<double>();
  for (std::int64_t i = 0; i < c.rows; ++i) {
    std::string s;
    char ch;
    while ((r.take(&ch, 1), ch != '\0')) s += ch;
    c.reasons.push_back(std::move(s));
  }
  if (!r.end()) throw std::runtime_error("a sweep chunk from another rank has trailing bytes");
  return c;
}

}  // namespace lgi::experiments

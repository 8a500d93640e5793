#pragma once
// FNV-1a, 64 bits (Fowler, Noll, Vo; the parameters of the IETF draft
// draft-eastlake-fnv): the checksum of lgi's checkpoints and of the finished
// rows of its partial files (run_checkpoint.hpp, sweep_row_hash.hpp,
// results_file.hpp). It finds damage, not tampering.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

namespace lgi::experiments {

class Fnv1a {
 public:
  static constexpr std::uint64_t offset_basis = 14695981039346656037ull;
  void bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h_ = (h_ ^ p[i]) * 1099511628211ull;
  }
  void bytes(std::span<const unsigned char> b) { bytes(b.data(), b.size()); }
  /// A number as its 8 bytes in memory (little-endian on every machine lgi builds on).
  template <class T>
  void value(T x) {
    static_assert(sizeof(T) == 8);
    bytes(&x, 8);
  }
  void values(const double* x, std::size_t n) { bytes(x, n * sizeof(double)); }
  std::uint64_t get() const { return h_; }

 private:
  std::uint64_t h_ = offset_basis;
};

}  // namespace lgi::experiments

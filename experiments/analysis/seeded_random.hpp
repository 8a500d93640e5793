#pragma once
// Random draws seeded per item, so that a result is a function of (seed,
// item) alone whatever the thread or rank that computes it: SplitMix64
// (G. Steele, D. Lea, C. Flood, "Fast splittable pseudorandom number
// generators", OOPSLA 2014) started from a hash of (seed, index, stream).
#include <cstdint>

namespace lgi::experiments {

/// SplitMix64's output function (finaliser).
constexpr std::uint64_t splitmix64_mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/// The draws of item `index` for one use (`stream`): a SplitMix64 sequence.
class CounterRng {
 public:
  CounterRng(std::uint64_t seed, std::int64_t index, std::uint64_t stream)
      : state_(splitmix64_mix(seed ^ splitmix64_mix(static_cast<std::uint64_t>(index) ^
                                                    splitmix64_mix(stream + 0x632be59bd9b4e019ULL)))) {}
  /// Uniform in [0, 1), 53 random bits.
  double uniform() {
    state_ += 0x9e3779b97f4a7c15ULL;
    return static_cast<double>(splitmix64_mix(state_) >> 11) * 0x1.0p-53;
  }

 private:
  std::uint64_t state_;
};

}  // namespace lgi::experiments

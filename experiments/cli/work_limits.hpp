#pragma once
// Up-front work limits (README.md, "Limits"; issue 50): a count past its
// limit is refused with exit 2 and one line naming the flag, before anything
// is allocated or written, so an absurd size (`poincare --ics 1e9`, a region
// raster of 10^10 cells) ends in a refusal within a second instead of hours
// of work, a full disk or an out-of-memory kill. The limits sit far above
// every run in the repository's docs; a larger study is split into runs.
#include <cstdint>
#include <string>

#include "experiments/errors/exit_status.hpp"

namespace lgi::experiments {

inline constexpr std::int64_t max_orbits = 10'000'000;           // poincare --ics, chaos-map cells x --ics
inline constexpr std::int64_t max_section_events = 10'000'000;   // poincare --max-events
inline constexpr std::int64_t max_grid_cells = 1'000'000;        // region / chaos-map (l, h) cells
inline constexpr std::int64_t max_branch_samples = 10'000'000;   // equilibria / bifurcation / region --samples
inline constexpr std::int64_t max_tori = 100'000;                // actions: --tori x the values of --l
inline constexpr std::int64_t max_samples_per_decade = 1'000'000;  // long-time --samples

/// Throws UsageError "<flag>: <count> <what> is above the limit of <limit> (README.md, Limits)".
inline void check_work_limit(const std::string& flag, std::int64_t count, std::int64_t limit,
                             const std::string& what) {
  if (count > limit)
    throw UsageError(flag + ": " + std::to_string(count) + " " + what + " is above the limit of " +
                     std::to_string(limit) + " (README.md, \"Limits\"; split the study into runs)");
}

/// a x b without overflow (saturates at INT64_MAX), for products of counts.
inline std::int64_t saturating_product(std::int64_t a, std::int64_t b) {
  std::int64_t p = 0;
  return __builtin_mul_overflow(a, b, &p) ? INT64_MAX : p;
}

}  // namespace lgi::experiments

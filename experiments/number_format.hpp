#pragma once
// How lgi prints numbers on stdout and in messages: one place, so every
// subcommand reads alike ("1.234e-05", never 17 digits of round-off).
#include <cmath>
#include <cstdio>
#include <string>

namespace lgi::experiments {

/// Scientific with `digits` decimals ("nan", "inf" as such): errors, CPU times.
inline std::string format_sci(double x, int digits = 3) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*e", digits, x);
  return buf;
}

/// Shortest general form with `digits` significant digits: steps, times, tolerances.
inline std::string format_general(double x, int digits = 6) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

}  // namespace lgi::experiments

#pragma once
// How lgi prints numbers on stdout, in CSV files and in messages: one place,
// so every subcommand reads alike ("1.234e-05", never 17 digits of round-off
// unless asked), with NaN and infinities spelled "nan", "inf", "-inf".
#include <cmath>
#include <cstdio>
#include <string>

namespace lgi::experiments {

namespace detail {
inline const char* non_finite_text(double x) { return std::isnan(x) ? "nan" : x > 0 ? "inf" : "-inf"; }
}  // namespace detail

/// Scientific with `digits` decimals: errors, CPU times.
inline std::string format_sci(double x, int digits = 3) {
  if (!std::isfinite(x)) return detail::non_finite_text(x);
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*e", digits, x);
  return buf;
}

/// Shortest general form with `digits` significant digits (printf's %g, as
/// an ostream with that precision prints): steps, times, tolerances.
inline std::string format_general(double x, int digits = 6) {
  if (!std::isfinite(x)) return detail::non_finite_text(x);
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

/// Every significant digit a double needs to be read back (%.17g): the tables a
/// reader compares bit for bit.
inline std::string format_exact(double x) { return format_general(x, 17); }

}  // namespace lgi::experiments

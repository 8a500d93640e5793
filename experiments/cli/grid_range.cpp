#include "experiments/cli/grid_range.hpp"

#include <cmath>
#include <sstream>

#include "experiments/errors/exit_status.hpp"

namespace lgi::experiments {

std::vector<double> parse_grid_range(const std::string& text, const std::string& flag) {
  std::istringstream in(text);
  double a = NAN, b = NAN;
  long long n = 0;
  char c1 = 0, c2 = 0;
  const bool parsed = static_cast<bool>(in >> a >> c1 >> b >> c2 >> n) && c1 == ':' && c2 == ':' && in.peek() == EOF;
  if (!parsed || !std::isfinite(a) || !std::isfinite(b) || n < 1 || n > 100000 || b < a || (n > 1 && !(a < b)))
    throw UsageError(flag + ": \"" + text + "\": expected a:b:n with a < b (a <= b for n = 1) and 1 <= n <= 100000");
  std::vector<double> out(static_cast<std::size_t>(n));
  for (long long k = 0; k < n; ++k)
    out[static_cast<std::size_t>(k)] = n == 1 ? a : a + (b - a) * static_cast<double>(k) / static_cast<double>(n - 1);
  if (n > 1) out.back() = b;
  return out;
}

}  // namespace lgi::experiments

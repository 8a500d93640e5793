#include "experiments/analysis/quantum/wigner_basis.hpp"

#include <cmath>
#include <cstdlib>

namespace lgi::experiments::quantum {

void WignerBasis::label(Eigen::Index i, int& j, int& k) const {
  j = jlo;
  while (offset(j + 1) <= i) ++j;
  k = static_cast<int>(i - offset(j)) - j;
}

double clebsch_gordan_1(int j1, int m1, int q, int J) {
  const int M = m1 + q;
  if (j1 < 0 || J < 0 || std::abs(q) > 1 || std::abs(m1) > j1 || std::abs(M) > J) return 0.0;
  const double j = j1, mm = M;
  if (J == j1 + 1) {
    const double d = (2 * j + 1) * (2 * j + 2);
    if (q == 1) return std::sqrt((j + mm) * (j + mm + 1) / d);
    if (q == 0) return std::sqrt((j - mm + 1) * (j + mm + 1) / ((2 * j + 1) * (j + 1)));
    return std::sqrt((j - mm) * (j - mm + 1) / d);
  }
  if (J == j1) {
    if (j1 == 0) return 0.0;  // 0 ⊗ 1 holds J = 1 only
    const double d = 2 * j * (j + 1);
    if (q == 1) return -std::sqrt((j + mm) * (j - mm + 1) / d);
    if (q == 0) return mm / std::sqrt(j * (j + 1));
    return std::sqrt((j - mm) * (j + mm + 1) / d);
  }
  if (J == j1 - 1) {
    const double d = 2 * j * (2 * j + 1);
    if (q == 1) return std::sqrt((j - mm) * (j - mm + 1) / d);
    if (q == 0) return -std::sqrt((j - mm) * (j + mm) / (j * (2 * j + 1)));
    return std::sqrt((j + mm + 1) * (j + mm) / d);
  }
  return 0.0;
}

}  // namespace lgi::experiments::quantum

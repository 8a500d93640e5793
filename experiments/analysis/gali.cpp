#include "experiments/analysis/gali.hpp"

#include <Eigen/SVD>
#include <cmath>

#include "experiments/analysis/seeded_random.hpp"

namespace lgi::experiments {

namespace {
constexpr std::uint64_t gali_stream = 0x6a11ULL;  // the draws of the deviation vectors
}  // namespace

GaliValues log10_gali(const integrators::Mat6& V) {
  // A fixed maximal size: the SVD allocates nothing.
  using Block = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>;
  GaliValues out{};
  for (int k = 2; k <= 6; ++k) {
    const Block A = V.leftCols(k);
    const Eigen::JacobiSVD<Block> svd(A);
    double sum = 0.0;
    for (int i = 0; i < k; ++i) sum += std::log10(svd.singularValues()(i));
    out[static_cast<std::size_t>(k - 2)] = sum;
  }
  return out;
}

integrators::Mat6 initial_deviation_vectors(std::uint64_t seed, std::int64_t index) {
  CounterRng rng(seed, index, gali_stream);
  integrators::Mat6 V;
  for (int c = 0; c < 6; ++c)
    for (int r = 0; r < 6; ++r) V(r, c) = 2.0 * rng.uniform() - 1.0;
  return V;
}

std::vector<double> gali_targets(double t_end, double dt, const GaliSampling& g) {
  const int n = g.samples;
  std::vector<double> t;
  if (n <= 1 || !(t_end > dt)) return {t_end};
  for (int j = 0; j < n - 1; ++j) {
    const double f = static_cast<double>(j) / static_cast<double>(n - 1);
    t.push_back(g.log_spacing ? dt * std::pow(t_end / dt, f) : t_end * static_cast<double>(j + 1) / static_cast<double>(n));
  }
  t.push_back(t_end);
  return t;
}

}  // namespace lgi::experiments

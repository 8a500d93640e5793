#include "experiments/analysis/chaos_indicators.hpp"

#include <algorithm>
#include <cmath>
#include <variant>

#include "experiments/analysis/seeded_random.hpp"
#include "experiments/io/trajectory_observer.hpp"
#include "integrators/system/model.hpp"

namespace lgi::experiments {

namespace {

/// Modified Gram–Schmidt on the columns of V in place; adds ln R_kk to sums.
/// False if a column vanished or is not finite.
bool orthonormalise(integrators::Mat6& V, std::array<double, 6>& sums) {
  for (int k = 0; k < 6; ++k) {
    for (int j = 0; j < k; ++j) V.col(k) -= V.col(j).dot(V.col(k)) * V.col(j);
    const double n = V.col(k).norm();
    if (!std::isfinite(n) || !(n > 0.0)) return false;
    V.col(k) /= n;
    sums[static_cast<std::size_t>(k)] += std::log(n);
  }
  return true;
}

template <class Model>
std::array<double, 6> spectrum_of(const Model& model, system::State x, double t_end, double dt) {
  integrators::Mat6 V = integrators::Mat6::Identity();
  std::array<double, 6> sums{};
  double t = 0.0;
  std::int64_t steps = 0;
  while (t < t_end) {  // the time grid of integrators::accumulate_chaos_indicators
    if (++steps % 256 == 0 && interrupt_requested.load(std::memory_order_relaxed)) {  // Ctrl-C
      sums.fill(std::nan(""));
      return sums;
    }
    const double h = (t_end - t) < 1.0000001 * dt ? t_end - t : dt;
    integrators::tangent_step(model, x, V, t, h);
    t = (t_end - t) < 1.0000001 * dt ? t_end : t + h;
    if (!orthonormalise(V, sums) || !x.Pi.allFinite()) {
      sums.fill(std::nan(""));
      return sums;
    }
  }
  for (double& s : sums) s /= t_end;
  return sums;
}

}  // namespace

integrators::Vec6 initial_tangent(std::uint64_t seed, std::int64_t index) {
  integrators::Vec6 v;
  std::uint64_t state = splitmix64_mix(seed ^ splitmix64_mix(static_cast<std::uint64_t>(index) ^ 0x7a1e5c0ffee15ULL));
  for (int k = 0; k < 6; ++k) {
    state += 0x9e3779b97f4a7c15ULL;
    v(k) = 2.0 * static_cast<double>(splitmix64_mix(state) >> 11) * 0x1.0p-53 - 1.0;
  }
  return v;
}

bool lyapunov_converged(double lyapunov, double last_half, double rtol) {
  const double scale = std::max(std::abs(lyapunov), std::abs(last_half));
  return std::isfinite(scale) && std::abs(last_half - lyapunov) <= rtol * scale;
}

StateIndicators state_indicators(const system::Scene& scene, const system::State& x0, const IndicatorSettings& s,
                                 std::int64_t index) {
  StateIndicators out;
  out.t_end = s.t_end;
  out.spectrum.fill(std::nan(""));
  const system::AnyModel model = system::make_model(scene);
  const integrators::ChaosIndicators r = std::visit(
      [&](const auto& m) {
        system::State x = x0;
        return integrators::chaos_indicators(m, x, initial_tangent(s.seed, index), 0.0, s.t_end, s.dt,
                                             &interrupt_requested);
      },
      model);
  out.ok = r.ok;
  out.lyapunov = r.lyapunov;
  out.lyapunov_last_half = r.lyapunov_last_half;
  out.megno = r.megno;
  out.converged = lyapunov_converged(r.lyapunov, r.lyapunov_last_half, s.rtol);
  if (s.spectrum) {
    out.spectrum = lyapunov_spectrum(scene, x0, s.t_end, s.dt);
    out.ok = out.ok && std::isfinite(out.spectrum[0]);
  }
  return out;
}

std::array<double, 6> lyapunov_spectrum(const system::Scene& scene, const system::State& x0, double t_end,
                                        double dt) {
  const system::AnyModel model = system::make_model(scene);
  return std::visit([&](const auto& m) { return spectrum_of(m, x0, t_end, dt); }, model);
}

}  // namespace lgi::experiments

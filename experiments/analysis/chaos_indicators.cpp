#include "experiments/analysis/chaos_indicators.hpp"

#include <algorithm>
#include <cmath>
#include <variant>

#include "experiments/analysis/seeded_random.hpp"
#include "experiments/analysis/tangent_loops.hpp"
#include "experiments/io/scene_suspension.hpp"
#include "experiments/io/trajectory_observer.hpp"
#include "integrators/system/model.hpp"
#include "integrators/torus/torus_tangent_flow.hpp"

namespace lgi::experiments {

namespace {

template <class Model>
std::array<double, 6> spectrum_of(const Model& model, system::State x, double t_end, double dt) {
  return spectrum_loop([&](double t, double h, integrators::Mat6& V) { integrators::tangent_step(model, x, V, t, h); },
                       [&] { return x.Pi.allFinite(); }, integrators::Mat6::Identity(), t_end, dt,
                       &interrupt_requested);
}

/// The fields every indicator run shares, from the loop's result.
StateIndicators from_loop(const integrators::ChaosIndicators& r, const IndicatorSettings& s) {
  StateIndicators out;
  out.t_end = s.t_end;
  out.spectrum.fill(std::nan(""));
  out.ok = r.ok;
  out.lyapunov = r.lyapunov;
  out.lyapunov_last_half = r.lyapunov_last_half;
  out.megno = r.megno;
  out.converged = lyapunov_converged(r.lyapunov, r.lyapunov_last_half, s.rtol);
  return out;
}

bool finite_curves(const GaliCurves& g) { return g.log10_gali.empty() || !std::isnan(g.log10_gali.back()[0]); }

std::vector<double> sample_times(const IndicatorSettings& s) {
  return gali_times(gali_targets(s.t_end, s.dt, s.gali_sampling), s.t_end, s.dt);
}

/// The loop's indicators with the spectrum and the GALI curves that `s` asks for
/// (spectrum() and gali() compute them); a non-finite one marks the run not ok.
template <class Spectrum, class Gali>
StateIndicators with_requested(StateIndicators out, const IndicatorSettings& s, Spectrum spectrum, Gali gali) {
  if (s.spectrum) {
    out.spectrum = spectrum();
    out.ok = out.ok && std::isfinite(out.spectrum[0]);
  }
  if (s.gali) {
    out.gali = gali();
    out.ok = out.ok && finite_curves(out.gali);
  }
  return out;
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
  const system::AnyModel model = system::make_model(scene);
  const integrators::ChaosIndicators r = std::visit(
      [&](const auto& m) {
        system::State x = x0;
        return integrators::chaos_indicators(m, x, initial_tangent(s.seed, index), 0.0, s.t_end, s.dt,
                                             &interrupt_requested);
      },
      model);
  return with_requested(
      from_loop(r, s), s, [&] { return lyapunov_spectrum(scene, x0, s.t_end, s.dt); },
      [&] { return gali_curves(scene, x0, s, index); });
}

GaliCurves gali_curves(const system::Scene& scene, const system::State& x0, const IndicatorSettings& s,
                       std::int64_t index) {
  const system::AnyModel model = system::make_model(scene);
  return std::visit(
      [&](const auto& m) {
        system::State x = x0;
        return gali_loop([&](double t, double h, integrators::Mat6& V) { integrators::tangent_step(m, x, V, t, h); },
                         [&] { return x.Pi.allFinite(); }, initial_deviation_vectors(s.seed, index), sample_times(s),
                         s.t_end, s.dt, &interrupt_requested);
      },
      model);
}

std::array<double, 6> lyapunov_spectrum(const system::Scene& scene, const system::State& x0, double t_end,
                                        double dt) {
  const system::AnyModel model = system::make_model(scene);
  return std::visit([&](const auto& m) { return spectrum_of(m, x0, t_end, dt); }, model);
}

StateIndicators cardan_state_indicators(const system::Scene& scene, const system::TorusState& x0,
                                        const IndicatorSettings& s, std::int64_t index) {
  const system::CardanTop top = cardan_top(scene);
  system::TorusState x = x0;
  const StateIndicators loop = from_loop(integrators::torus::torus_chaos_indicators(
                                            top, x, initial_tangent(s.seed, index), s.t_end, s.dt, &interrupt_requested),
                                        s);
  const auto spectrum = [&] {
    // Not from the identity: δq₁ is exactly invariant where q₁ is cyclic, and
    // would hold the first Gram–Schmidt column at λ = 0.
    system::Vec6 y = system::stack(x0);
    std::array<double, 6> unused{};
    integrators::Mat6 V = initial_deviation_vectors(s.seed, index);
    orthonormalise(V, unused);
    return spectrum_loop(
        [&](double, double h, integrators::Mat6& W) { integrators::torus::torus_tangent_step(top, y, W, h); },
        [&] { return y.allFinite(); }, V, s.t_end, s.dt, &interrupt_requested);
  };
  return with_requested(loop, s, spectrum, [&] { return cardan_gali_curves(scene, x0, s, index); });
}

GaliCurves cardan_gali_curves(const system::Scene& scene, const system::TorusState& x0, const IndicatorSettings& s,
                              std::int64_t index) {
  const system::CardanTop top = cardan_top(scene);
  system::Vec6 y = system::stack(x0);
  return gali_loop([&](double, double h, integrators::Mat6& V) { integrators::torus::torus_tangent_step(top, y, V, h); },
                   [&] { return y.allFinite(); }, initial_deviation_vectors(s.seed, index), sample_times(s), s.t_end,
                   s.dt, &interrupt_requested);
}

}  // namespace lgi::experiments

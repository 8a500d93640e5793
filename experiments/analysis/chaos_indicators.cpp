#include "experiments/analysis/chaos_indicators.hpp"

#include <algorithm>
#include <cmath>
#include <variant>

#include "experiments/analysis/seeded_random.hpp"
#include "experiments/analysis/tangent_loops.hpp"
#include "experiments/io/scene_suspension.hpp"
#include "experiments/io/trajectory_observer.hpp"
#include "integrators/ensemble/tangent_ensemble.hpp"
#include "integrators/system/model.hpp"
#include "integrators/ensemble/cardan_tangent_ensemble.hpp"

namespace lgi::experiments {

namespace {


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
  return gali_times(gali_targets(s.t_end, s.dt, s.gali_sampling), s.t_end, s.dt, &interrupt_requested);
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

namespace {

/// λ and ⟨Y⟩ from the loop's result r, then the spectrum and GALI as asked.
StateIndicators with_extras(const integrators::ChaosIndicators& r, const system::Scene& scene, const system::State& x0,
                            const IndicatorSettings& s, std::int64_t index) {
  return with_requested(
      from_loop(r, s), s, [&] { return lyapunov_spectrum(scene, x0, s.t_end, s.dt); },
      [&] { return gali_curves(scene, x0, s, index); });
}

}  // namespace

StateIndicators state_indicators(const system::Scene& scene, const system::State& x0, const IndicatorSettings& s,
                                 std::int64_t index) {
  const system::AnyModel model = system::make_model(scene);
  const integrators::ChaosIndicators r = integrators::ensemble::with_tangent_step(model, [&](auto step) {
    system::State x = x0;
    integrators::Vec6 v = initial_tangent(s.seed, index);
    return integrators::accumulate_chaos_indicators([&](double t, double h, integrators::Vec6& w) { step(x, w, t, h); },
                                                    [&] { return x.Pi.allFinite(); }, v, 0.0, s.t_end, s.dt,
                                                    &interrupt_requested);
  });
  return with_extras(r, scene, x0, s, index);
}

void state_indicators(const system::Scene& scene, std::span<const system::State> x0, const IndicatorSettings& s,
                      std::int64_t first_index, std::optional<integrators::ensemble::Isa> isa,
                      std::span<StateIndicators> out) {
  const system::AnyModel model = system::make_model(scene);
  std::optional<integrators::ensemble::TangentEnsemble> e;
  if (isa) e = integrators::ensemble::TangentEnsemble::make(model, *isa);
  const auto index = [&](std::size_t k) { return first_index + static_cast<std::int64_t>(k); };
  std::size_t first = 0;
  while (first < x0.size()) {
    if (!e) {
      out[first] = state_indicators(scene, x0[first], s, index(first));
      ++first;
      continue;
    }
    const std::size_t n = std::min(x0.size() - first, static_cast<std::size_t>(e->lanes()));
    for (std::size_t l = 0; l < n; ++l)
      e->set_lane(static_cast<int>(l), x0[first + l], initial_tangent(s.seed, index(first + l)));
    integrators::ChaosIndicators r[integrators::ensemble::max_lanes];
    e->chaos_indicators(0.0, s.t_end, s.dt, &interrupt_requested, {r, n});
    for (std::size_t l = 0; l < n; ++l) out[first + l] = with_extras(r[l], scene, x0[first + l], s, index(first + l));
    first += n;
  }
}

GaliCurves gali_curves(const system::Scene& scene, const system::State& x0, const IndicatorSettings& s,
                       std::int64_t index) {
  const system::AnyModel model = system::make_model(scene);
  return integrators::ensemble::with_tangent_step(model, [&](auto step) {
    system::State x = x0;
    return gali_loop([&](double t, double h, integrators::Mat6& V) { step(x, V, t, h); },
                     [&] { return x.Pi.allFinite(); }, initial_deviation_vectors(s.seed, index), sample_times(s),
                     s.t_end, s.dt, &interrupt_requested);
  });
}

std::array<double, 6> lyapunov_spectrum(const system::Scene& scene, const system::State& x0, double t_end,
                                        double dt) {
  const system::AnyModel model = system::make_model(scene);
  return integrators::ensemble::with_tangent_step(model, [&](auto step) {
    system::State x = x0;
    return spectrum_loop([&](double t, double h, integrators::Mat6& V) { step(x, V, t, h); },
                         [&] { return x.Pi.allFinite(); }, integrators::Mat6::Identity(), t_end, dt,
                         &interrupt_requested);
  });
}

StateIndicators cardan_state_indicators(const system::Scene& scene, const system::TorusState& x0,
                                        const IndicatorSettings& s, std::int64_t index) {
  const integrators::ensemble::CardanLaneModel m = integrators::ensemble::cardan_lane_model(cardan_top(scene));
  system::Vec6 x = system::stack(x0);
  const StateIndicators loop = from_loop(integrators::ensemble::scalar_cardan_chaos_indicators(
                                             m, x, initial_tangent(s.seed, index), s.t_end, s.dt, &interrupt_requested),
                                         s);
  const auto spectrum = [&] {
    // Not from the identity: δq₁ is exactly invariant where q₁ is cyclic, and
    // would hold the first Gram–Schmidt column at λ = 0.
    system::Vec6 y = system::stack(x0);
    std::array<double, 6> unused{};
    integrators::Mat6 V = initial_deviation_vectors(s.seed, index);
    orthonormalise(V, unused);
    return spectrum_loop(
        [&](double, double h, integrators::Mat6& W) { integrators::ensemble::scalar_cardan_tangent_step(m, y, W, h); },
        [&] { return y.allFinite(); }, V, s.t_end, s.dt, &interrupt_requested);
  };
  return with_requested(loop, s, spectrum, [&] { return cardan_gali_curves(scene, x0, s, index); });
}

GaliCurves cardan_gali_curves(const system::Scene& scene, const system::TorusState& x0, const IndicatorSettings& s,
                              std::int64_t index) {
  const integrators::ensemble::CardanLaneModel m = integrators::ensemble::cardan_lane_model(cardan_top(scene));
  system::Vec6 y = system::stack(x0);
  return gali_loop(
      [&](double, double h, integrators::Mat6& V) { integrators::ensemble::scalar_cardan_tangent_step(m, y, V, h); },
      [&] { return y.allFinite(); }, initial_deviation_vectors(s.seed, index), sample_times(s), s.t_end, s.dt,
      &interrupt_requested);
}

}  // namespace lgi::experiments

// The scalar tangent step of the models with a kernel and the ensemble of
// tangent flows (tangent_ensemble.hpp). Compiled for the baseline
// instruction set: the step is tangent_kernel.hpp on double.
#include "integrators/ensemble/tangent_ensemble.hpp"

#include <cmath>

#include "integrators/ensemble/tangent_kernel.hpp"
#include "integrators/core/loop_support.hpp"

namespace lgi::integrators::ensemble {

namespace {

Eigen::Index col(std::size_t k) { return static_cast<Eigen::Index>(k); }

template <std::size_t NV, class Vectors>
void step_double(const EnsembleModel& model, State& x, Vectors& V, double t, double h) {
  M3<double> R;
  V3<double> Pi;
  Tangent6<double> v[NV];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) R.m[i][j] = x.R(i, j);
    Pi.v[i] = x.Pi(i);
    for (std::size_t k = 0; k < NV; ++k) v[k].xi.v[i] = V(i, col(k)), v[k].dPi.v[i] = V(3 + i, col(k));
  }
  tangent_rk_step<NV>(model, R, Pi, v, t, h);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) x.R(i, j) = R.m[i][j];
    x.Pi(i) = Pi.v[i];
    for (std::size_t k = 0; k < NV; ++k) V(i, col(k)) = v[k].xi.v[i], V(3 + i, col(k)) = v[k].dPi.v[i];
  }
}

}  // namespace

void scalar_tangent_step(const EnsembleModel& model, State& x, Vec6& v, double t, double h) {
  step_double<1>(model, x, v, t, h);
}
void scalar_tangent_step(const EnsembleModel& model, State& x, Mat6& V, double t, double h) {
  step_double<6>(model, x, V, t, h);
}

std::optional<TangentEnsemble> TangentEnsemble::make(const system::AnyModel& model, Isa isa, int vectors) {
  const std::optional<EnsembleModel> m = ensemble_model(model);
  if (!m || !isa_available(isa) || (vectors != 1 && vectors != 6)) return std::nullopt;
  TangentEnsemble e;
  e.model_ = *m;
  e.kernels_ = tangent_kernels(isa);
  e.isa_ = isa;
  e.lanes_ = e.kernels_.lanes;
  e.vectors_ = vectors;
  return e;
}

void TangentEnsemble::set_lane(int lane, const State& s, const Vec6& v) {
  const auto l = static_cast<std::size_t>(lane);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) block_.row[3 * i + j][l] = s.R(i, j);
    block_.row[9 + i][l] = s.Pi(i);
  }
  for (int c = 0; c < 6; ++c) block_.row[tangent_row(0, c)][l] = v(c);
}
void TangentEnsemble::set_lane(int lane, const State& s, const Mat6& V) {
  set_lane(lane, s, Vec6(V.col(0)));
  for (int k = 1; k < 6; ++k)
    for (int c = 0; c < 6; ++c) block_.row[tangent_row(k, c)][static_cast<std::size_t>(lane)] = V(c, k);
}
void TangentEnsemble::get_lane(int lane, State& s, Vec6& v) const {
  const auto l = static_cast<std::size_t>(lane);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) s.R(i, j) = block_.row[3 * i + j][l];
    s.Pi(i) = block_.row[9 + i][l];
  }
  for (int c = 0; c < 6; ++c) v(c) = block_.row[tangent_row(0, c)][l];
}
void TangentEnsemble::get_lane(int lane, State& s, Mat6& V) const {
  Vec6 first;
  get_lane(lane, s, first);
  V.col(0) = first;
  for (int k = 1; k < 6; ++k)
    for (int c = 0; c < 6; ++c) V(c, k) = block_.row[tangent_row(k, c)][static_cast<std::size_t>(lane)];
}

void TangentEnsemble::step(double t, double h) {
  (vectors_ == 6 ? kernels_.step_six : kernels_.step_one)(model_, block_, t, h);
}

bool begin_chaos_outputs(std::span<ChaosIndicators> out, double t0, double t_end, double dt) {
  for (ChaosIndicators& r : out) r = ChaosIndicators{};
  if (out.empty()) return false;
  if (!fixed_step_grid_problem(t0, t_end, dt).empty()) {  // as accumulate_chaos_indicators
    for (ChaosIndicators& r : out) r.ok = false, r.lyapunov = r.megno = r.megno_y = std::nan("");
    return false;
  }
  return true;
}

void TangentEnsemble::chaos_indicators(double t0, double t_end, double dt, const std::atomic<bool>* stop,
                                       std::span<ChaosIndicators> out) {
  if (!begin_chaos_outputs(out, t0, t_end, dt)) return;
  const int n = static_cast<int>(out.size());
  chaos_ = ChaosLanes{};
  chaos_.t = t0;
  for (int l = 0; l < lanes_; ++l) {  // v.normalize() as the scalar loop; padding: lane 0's copy
    State s;
    Vec6 v;
    get_lane(l < n ? l : 0, s, v);
    v.normalize();
    set_lane(l, s, v);
    chaos_.running[l] = l < n ? 1.0 : 0.0;
  }
  const bool stopped = run_chaos_lanes(
      chaos_, n, t_end, stop, [&](ChaosLanes& c) { kernels_.chaos(model_, block_, c, t0, t_end, dt, 256); });
  chaos_lane_results(chaos_, stopped, out);
}

void chaos_lane_results(const ChaosLanes& c, bool stopped, std::span<ChaosIndicators> out) {
  const double nan = std::nan("");
  for (std::size_t l = 0; l < out.size(); ++l) {
    ChaosIndicators& r = out[l];
    r.steps = static_cast<std::int64_t>(c.steps[l]);
    if (c.running[l] == 0.0 || stopped) {
      r.ok = false;
      r.stopped = c.running[l] != 0.0;
      r.lyapunov = r.megno = r.megno_y = r.lyapunov_last_half = nan;
      continue;
    }
    // ChaosAccumulator's lyapunov(), lyapunov_since_mark(), mean_megno(), megno()
    const double s = c.s;
    r.lyapunov = s > 0.0 ? c.log_sum[l] / s : 0.0;
    r.lyapunov_last_half = s > c.marked_s ? (c.log_sum[l] - c.marked_log_sum[l]) / (s - c.marked_s) : nan;
    r.megno = s > 0.0 ? c.mean_sum[l] / s : 0.0;
    r.megno_y = c.y[l];
  }
}

}  // namespace lgi::integrators::ensemble

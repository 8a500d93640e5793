// The Cardan top's scalar tangent step and its ensemble in lanes
// (cardan_tangent_ensemble.hpp). Compiled for the baseline instruction set:
// the scalar step is cardan_tangent_kernel.hpp on double.
#include "integrators/ensemble/cardan_tangent_ensemble.hpp"

#include <cmath>

#include "integrators/ensemble/cardan_tangent_kernel.hpp"
#include "integrators/ensemble/tangent_ensemble.hpp"
#include "integrators/core/loop_support.hpp"

namespace lgi::integrators::ensemble {

namespace {

template <std::size_t NV, class Vectors>
void step_double(const CardanLaneModel& model, system::Vec6& x, Vectors& V, double h) {
  double y[6];
  double v[NV][6];
  for (int c = 0; c < 6; ++c) {
    y[c] = x(c);
    for (std::size_t k = 0; k < NV; ++k) v[k][c] = V(c, static_cast<Eigen::Index>(k));
  }
  cardan_tangent_rk_step<NV>(model, y, v, h);
  for (int c = 0; c < 6; ++c) {
    x(c) = y[c];
    for (std::size_t k = 0; k < NV; ++k) V(c, static_cast<Eigen::Index>(k)) = v[k][c];
  }
}

void copy3(const lie::Vec3& v, double scale, double (&out)[3]) {
  for (int i = 0; i < 3; ++i) out[i] = scale * v(i);
}

}  // namespace

CardanLaneModel cardan_lane_model(const system::CardanTop& top) {
  CardanLaneModel m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m.J[i][j] = top.J(i, j);
  const system::SuspensionParameters& s = top.suspension;
  copy3(s.inner_inertia, 1.0, m.inner);
  m.outer = s.outer_inertia;
  copy3(top.pedestal().transpose() * lie::Vec3::UnitZ(), 1.0, m.gamma);
  copy3(top.mass * top.chi, top.g, m.body);
  copy3(s.inner_mass * s.inner_center, top.g, m.inner_moment);
  copy3(s.outer_mass * s.outer_center, top.g, m.outer_moment);
  m.potential = top.g != 0.0;
  m.tilted = m.gamma[0] != 0.0 || m.gamma[1] != 0.0;
  return m;
}

void scalar_cardan_tangent_step(const CardanLaneModel& model, system::Vec6& x, Vec6& v, double h) {
  step_double<1>(model, x, v, h);
}
void scalar_cardan_tangent_step(const CardanLaneModel& model, system::Vec6& x, Mat6& V, double h) {
  step_double<6>(model, x, V, h);
}

ChaosIndicators scalar_cardan_chaos_indicators(const CardanLaneModel& model, system::Vec6& x, Vec6 v, double t_end,
                                               double dt, const std::atomic<bool>* stop) {
  system::Vec6 y = x;
  const ChaosIndicators out = accumulate_chaos_indicators(
      [&](double, double h, Vec6& w) { scalar_cardan_tangent_step(model, y, w, h); }, [&] { return y.allFinite(); },
      v, 0.0, t_end, dt, stop);
  if (out.ok) x = y;
  return out;
}

std::optional<CardanTangentEnsemble> CardanTangentEnsemble::make(const system::CardanTop& top, Isa isa,
                                                                 int vectors) {
  if (!isa_available(isa) || (vectors != 1 && vectors != 6)) return std::nullopt;
  CardanTangentEnsemble e;
  e.model_ = cardan_lane_model(top);
  e.kernels_ = cardan_tangent_kernels(isa);
  e.isa_ = isa;
  e.lanes_ = e.kernels_.lanes;
  e.vectors_ = vectors;
  return e;
}

void CardanTangentEnsemble::set_lane(int lane, const system::Vec6& x, const Vec6& v) {
  const auto l = static_cast<std::size_t>(lane);
  for (int c = 0; c < 6; ++c) block_.row[c][l] = x(c), block_.row[tangent_row(0, c)][l] = v(c);
}
void CardanTangentEnsemble::set_lane(int lane, const system::Vec6& x, const Mat6& V) {
  set_lane(lane, x, Vec6(V.col(0)));
  for (int k = 1; k < 6; ++k)
    for (int c = 0; c < 6; ++c) block_.row[tangent_row(k, c)][static_cast<std::size_t>(lane)] = V(c, k);
}
void CardanTangentEnsemble::get_lane(int lane, system::Vec6& x, Vec6& v) const {
  const auto l = static_cast<std::size_t>(lane);
  for (int c = 0; c < 6; ++c) x(c) = block_.row[c][l], v(c) = block_.row[tangent_row(0, c)][l];
}
void CardanTangentEnsemble::get_lane(int lane, system::Vec6& x, Mat6& V) const {
  Vec6 first;
  get_lane(lane, x, first);
  V.col(0) = first;
  for (int k = 1; k < 6; ++k)
    for (int c = 0; c < 6; ++c) V(c, k) = block_.row[tangent_row(k, c)][static_cast<std::size_t>(lane)];
}

void CardanTangentEnsemble::step(double h) { (vectors_ == 6 ? kernels_.step_six : kernels_.step_one)(model_, block_, h); }

void CardanTangentEnsemble::chaos_indicators(double t0, double t_end, double dt, const std::atomic<bool>* stop,
                                             std::span<ChaosIndicators> out) {
  if (!begin_chaos_outputs(out, t0, t_end, dt)) return;
  const int n = static_cast<int>(out.size());
  chaos_ = ChaosLanes{};
  chaos_.t = t0;
  for (int l = 0; l < lanes_; ++l) {  // v.normalize() as the scalar loop; padding: lane 0's copy
    system::Vec6 x;
    Vec6 v;
    get_lane(l < n ? l : 0, x, v);
    v.normalize();
    set_lane(l, x, v);
    chaos_.running[l] = l < n ? 1.0 : 0.0;
  }
  const bool stopped = run_chaos_lanes(
      chaos_, n, t_end, stop, [&](ChaosLanes& c) { kernels_.chaos(model_, block_, c, t0, t_end, dt, 256); });
  chaos_lane_results(chaos_, stopped, out);
}

}  // namespace lgi::integrators::ensemble

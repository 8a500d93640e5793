#include "experiments/analysis/periodic/periodic_flow.hpp"

#include <cmath>
#include <numbers>

#include "experiments/io/trajectory_observer.hpp"  // interrupt_requested
#include "integrators/core/torus_tangent_flow.hpp"

namespace lgi::experiments {

namespace {

constexpr double two_pi = 2.0 * std::numbers::pi;

/// The reduced map's end: q1 put back where it started, the drift kept; each
/// piece's tangent flow gets the q1 row e_q1ᵀ (their product is the reduced
/// monodromy, as q1 is cyclic: M e_q1 = e_q1).
void reduce(Shot& s, const Vec6& x0) {
  s.drift = s.end(0) - x0(0);
  s.end(0) = x0(0);
  s.pieces.back().end(0) = x0(0);
  for (MonodromyPiece& p : s.pieces) p.monodromy.row(0) = Vec6::Unit(0).transpose();
  s.monodromy = pieces_product(s.pieces);
}

Shot shoot_cardan(const system::CardanTop& top, const Vec6& x0, double T, double dt) {
  Shot s{x0, Mat6::Identity(), true};
  Mat6 X = Mat6::Identity();
  Vec6 start = x0;
  const auto n = static_cast<long>(std::ceil(std::abs(T) / dt - 1e-9));
  const long steps = n < 1 ? 1 : n;
  const double h = T / static_cast<double>(steps);
  for (long k = 0; k < steps && s.ok; ++k) {
    integrators::torus::torus_tangent_step(top, s.end, X, h);
    // Ctrl-C read every step, as the heavy top's shoot (euler_poisson_flow.cpp).
    s.ok = s.end.allFinite() && X.allFinite() && !interrupt_requested.load(std::memory_order_relaxed);
    if (k + 1 < steps && X.cwiseAbs().maxCoeff() > piece_growth) cut_piece(s, start, X);
  }
  cut_piece(s, start, X);
  reduce(s, x0);
  return s;
}

}  // namespace

Vec6 flow_field(const PeriodicFlow& flow, const Vec6& x) {
  if (!flow.cardan) return euler_poisson_field(flow.body, x);
  Vec6 f = flow.cardan->field(system::unstack(x));
  f(0) = 0.0;
  return f;
}

Mat6 flow_jacobian(const PeriodicFlow& flow, const Vec6& x) {
  if (!flow.cardan) return euler_poisson_jacobian(flow.body, x);
  Mat6 A = integrators::torus::torus_tangent_rate(*flow.cardan, x, Mat6(Mat6::Identity()));
  A.row(0).setZero();
  return A;
}

Invariants flow_invariants(const PeriodicFlow& flow, const Vec6& x) {
  if (!flow.cardan) return euler_poisson_invariants(flow.body, x);
  const system::TorusState s = system::unstack(x);
  Invariants v;
  v.value << flow.cardan->energy(s), x(3), x(0);
  v.gradients.setZero();
  v.gradients.row(0) = flow.cardan->energy_gradient(s).transpose();
  v.gradients(1, 3) = 1.0;
  v.gradients(2, 0) = 1.0;
  return v;
}

Eigen::Vector3d invariant_levels(const PeriodicFlow& flow, double h, double l) {
  return {h, l, flow.cardan ? 0.0 : 1.0};
}

Vec6 flow_difference(const PeriodicFlow& flow, const Vec6& end, const Vec6& start) {
  Vec6 d = end - start;
  if (flow.cardan)
    for (int k = 1; k < 3; ++k) d(k) -= two_pi * std::floor(d(k) / two_pi + 0.5);
  return d;
}

Shot shoot(const PeriodicFlow& flow, const Vec6& x0, double T, double dt) {
  return flow.cardan ? shoot_cardan(*flow.cardan, x0, T, dt) : shoot(flow.body, x0, T, dt);
}

bool flow_step(const PeriodicFlow& flow, Vec6& x, double h) {
  if (!flow.cardan) return flow_step(flow.body, x, h);
  const double q1 = x(0);
  Vec6 unused = Vec6::Zero();
  integrators::torus::torus_tangent_step(*flow.cardan, x, unused, h);
  x(0) = q1;
  return x.allFinite();
}

}  // namespace lgi::experiments

#include "experiments/analysis/periodic/euler_poisson_flow.hpp"

#include <Eigen/LU>
#include <array>
#include <cmath>
#include <limits>

#include "experiments/io/trajectory_observer.hpp"  // interrupt_requested

namespace lgi::experiments {

namespace {

Eigen::Matrix3d hat(const Vec3& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

/// The nine substep fractions of the triple jump applied twice to the midpoint rule.
std::array<double, 9> composition_weights() {
  const double c4 = std::cbrt(2.0), c6 = std::pow(2.0, 0.2);
  const double a1 = 1.0 / (2.0 - c4), a0 = -c4 / (2.0 - c4);  // order 4 from order 2
  const double b1 = 1.0 / (2.0 - c6), b0 = -c6 / (2.0 - c6);  // order 6 from order 4
  const std::array<double, 3> inner = {a1, a0, a1}, outer = {b1, b0, b1};
  std::array<double, 9> w{};
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) w[3 * i + j] = outer[i] * inner[j];
  return w;
}

/// One implicit midpoint substep of size h: x ← x + h f((x + x')/2), X ← its derivative.
/// Newton's method on the midpoint m: m − x − (h/2) f(m) = 0.
bool midpoint_substep(const HeavyTopBody& body, Vec6& x, Mat6* X, double h) {
  Vec6 m = x + 0.5 * h * euler_poisson_field(body, x);
  for (int it = 0; it < 30; ++it) {
    const Vec6 r = m - x - 0.5 * h * euler_poisson_field(body, m);
    const Mat6 D = Mat6::Identity() - 0.5 * h * euler_poisson_jacobian(body, m);
    const Vec6 dm = D.partialPivLu().solve(r);
    m -= dm;
    // A few ulps: a bound below half an ulp of m would never be met once |m| ≳ 9.
    if (dm.norm() <= 4.0 * std::numeric_limits<double>::epsilon() * (1.0 + m.norm())) break;
    if (it == 29 || !m.allFinite()) return false;
  }
  if (X) {
    const Mat6 A = 0.5 * h * euler_poisson_jacobian(body, m);
    *X = (Mat6::Identity() - A).partialPivLu().solve((Mat6::Identity() + A) * *X);
  }
  x = 2.0 * m - x;
  return x.allFinite();
}

}  // namespace

Vec6 euler_poisson_field(const HeavyTopBody& body, const Vec6& x) {
  const Vec3 Pi = x.head<3>(), G = x.tail<3>();
  const Vec3 Omega = body.J.inverse() * Pi;
  Vec6 f;
  f.head<3>() = Pi.cross(Omega) + G.cross(body.weight);
  f.tail<3>() = G.cross(Omega);
  return f;
}

Mat6 euler_poisson_jacobian(const HeavyTopBody& body, const Vec6& x) {
  const Vec3 Pi = x.head<3>(), G = x.tail<3>();
  const Eigen::Matrix3d Jinv = body.J.inverse();
  const Vec3 Omega = Jinv * Pi;
  Mat6 A;
  A.topLeftCorner<3, 3>() = -hat(Omega) + hat(Pi) * Jinv;
  A.topRightCorner<3, 3>() = -hat(body.weight);
  A.bottomLeftCorner<3, 3>() = hat(G) * Jinv;
  A.bottomRightCorner<3, 3>() = -hat(Omega);
  return A;
}

Invariants euler_poisson_invariants(const HeavyTopBody& body, const Vec6& x) {
  const Vec3 Pi = x.head<3>(), G = x.tail<3>();
  const Vec3 Omega = body.J.inverse() * Pi;
  Invariants v;
  v.value << 0.5 * Pi.dot(Omega) + body.weight.dot(G), Pi.dot(G), G.squaredNorm();
  v.gradients.setZero();
  v.gradients.block<1, 3>(0, 0) = Omega.transpose();
  v.gradients.block<1, 3>(0, 3) = body.weight.transpose();
  v.gradients.block<1, 3>(1, 0) = G.transpose();
  v.gradients.block<1, 3>(1, 3) = Pi.transpose();
  v.gradients.block<1, 3>(2, 3) = 2.0 * G.transpose();
  return v;
}

void cut_piece(Shot& s, Vec6& start, Mat6& X) {
  s.pieces.push_back({start, s.end, X});
  start = s.end;
  X.setIdentity();
}

Mat6 pieces_product(const std::vector<MonodromyPiece>& pieces) {
  if (pieces.size() == 1) return pieces.front().monodromy;
  Mat6 product = Mat6::Identity();
  for (const MonodromyPiece& p : pieces) product = p.monodromy * product;
  return product;
}

Shot shoot(const HeavyTopBody& body, const Vec6& x0, double T, double dt) {
  static const std::array<double, 9> w = composition_weights();
  Shot s{x0, Mat6::Identity(), true};
  Mat6 X = Mat6::Identity();
  Vec6 start = x0;
  const auto n = static_cast<long>(std::ceil(std::abs(T) / dt - 1e-9));
  const long steps = n < 1 ? 1 : n;
  const double h = T / static_cast<double>(steps);
  for (long k = 0; k < steps && s.ok; ++k) {
    // Ctrl-C: one shot over a long period is seconds of work; a step is microseconds, so a load a step is free.
    if (interrupt_requested.load(std::memory_order_relaxed)) s.ok = false;
    for (const double wi : w) s.ok = s.ok && midpoint_substep(body, s.end, &X, wi * h);
    if (k + 1 < steps && X.cwiseAbs().maxCoeff() > piece_growth) cut_piece(s, start, X);
  }
  cut_piece(s, start, X);
  s.monodromy = pieces_product(s.pieces);
  return s;
}

bool flow_step(const HeavyTopBody& body, Vec6& x, double h) {
  static const std::array<double, 9> w = composition_weights();
  bool ok = true;
  for (const double wi : w) ok = ok && midpoint_substep(body, x, nullptr, wi * h);
  return ok;
}

}  // namespace lgi::experiments

#include "experiments/analysis/cardan_equilibria.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "experiments/errors/input_error.hpp"

namespace lgi::experiments {
namespace {

using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;
using std::numbers::pi;

double torus_distance(const Vec2& a, const Vec2& b) {
  return std::hypot(wrap_angle_signed(a(0) - b(0)), wrap_angle_signed(a(1) - b(1)));
}

/// U_ℓ (amended) or W_ω (augmented) on the shape torus (q2, q3), q1 = 0 (top of the header).
struct ShapePotential {
  const system::CardanTop& top;
  bool amended = true;
  double parameter = 0.0;  // ℓ or ω

  static Vec3 config(const Vec2& r) { return {0.0, r(0), r(1)}; }
  double locked_inertia(const Vec2& r) const { return top.mass_matrix(config(r))(0, 0); }
  double value(const Vec2& r) const {
    const double m = locked_inertia(r), V = top.potential(config(r));
    return amended ? V + parameter * parameter / (2.0 * m) : V - 0.5 * parameter * parameter * m;
  }
  Vec2 gradient(const Vec2& r) const {
    const Vec3 q = config(r);
    const auto dM = top.mass_matrix_derivatives(q);
    const Vec3 dV = top.potential_gradient(q);
    const double m = top.mass_matrix(q)(0, 0);
    const double c = amended ? -parameter * parameter / (2.0 * m * m) : -0.5 * parameter * parameter;
    return {dV(1) + c * dM[1](0, 0), dV(2) + c * dM[2](0, 0)};
  }
  /// Central differences of the exact gradient (step 1e-5; the Newton
  /// iteration's limit does not depend on it, only the classification's last digits).
  Mat2 hessian(const Vec2& r) const {
    constexpr double d = 1e-5;
    Mat2 H;
    for (int k = 0; k < 2; ++k) {
      Vec2 a = r, b = r;
      a(k) += d, b(k) -= d;
      H.col(k) = (gradient(a) - gradient(b)) / (2.0 * d);
    }
    return 0.5 * (H + H.transpose());
  }
  /// ω at a relative equilibrium and its ℓ, h.
  void motion(const Vec2& r, double& omega, double& l, double& h) const {
    const double m = locked_inertia(r), V = top.potential(config(r));
    omega = amended ? parameter / m : parameter;
    l = omega * m;
    h = V + 0.5 * omega * omega * m;
  }
};

struct ShapeCriticalPoint {
  Vec2 r;
  bool degenerate = false;
  double residual = 0.0;
};

/// Newton from r with a pseudo-inverse (degenerate circles are reached too),
/// steps clipped to 0.5 rad. False if it does not reach |∇| ≤ tol.
bool newton(const ShapePotential& P, Vec2& r, double tol) {
  for (int it = 0; it < 80; ++it) {
    const Vec2 g = P.gradient(r);
    if (!g.allFinite()) return false;
    if (g.norm() <= tol) return true;
    Vec2 step = -P.hessian(r).completeOrthogonalDecomposition().solve(g);
    if (!step.allFinite()) return false;
    if (step.norm() > 0.5) step *= 0.5 / step.norm();
    r += step;
    if (step.norm() < 1e-15 * (1.0 + r.norm())) return P.gradient(r).norm() <= tol;
  }
  return P.gradient(r).norm() <= tol;
}

/// A circle of critical points along q3 is reported at q3 = 0 (header).
void canonicalise(const ShapePotential& P, ShapeCriticalPoint& c, double tol, double value_scale) {
  c.r = {wrap_angle_signed(c.r(0)), wrap_angle_positive(c.r(1))};
  if (std::abs(std::sin(c.r(0))) < 1e-9) {  // a pole: exactly 0 or π if it is critical there
    const Vec2 pole(std::cos(c.r(0)) > 0.0 ? 0.0 : pi, c.r(1));
    if (P.gradient(pole).norm() <= tol) c.r = pole;
  }
  const Eigen::SelfAdjointEigenSolver<Mat2> es(P.hessian(c.r));
  const double big = std::max(es.eigenvalues().cwiseAbs().maxCoeff(), value_scale);
  const bool flat = std::abs(es.eigenvalues()(0)) < 1e-6 * big || std::abs(es.eigenvalues()(1)) < 1e-6 * big;
  if (!flat) return;
  const Vec2 at_zero(c.r(0), 0.0);
  bool circle = P.gradient(at_zero).norm() <= tol;
  for (int k = 1; circle && k < 8; ++k)
    circle = std::abs(P.value(Vec2(c.r(0), k * pi / 4.0)) - P.value(at_zero)) <= 1e-10 * value_scale;
  if (circle) c.r = at_zero;
  c.degenerate = true;
}

std::vector<ShapeCriticalPoint> critical_points(const ShapePotential& P, int grid) {
  const int n = std::max(grid, 8);
  const double d = 2.0 * pi / n;
  std::vector<Vec2> g(static_cast<std::size_t>((n + 1) * (n + 1)));
  double g_scale = 0.0, v_scale = 0.0;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const Vec2 r(-pi + i * d, j * d);
      g[static_cast<std::size_t>(i * (n + 1) + j)] = P.gradient(r);
      g_scale = std::max(g_scale, g[static_cast<std::size_t>(i * (n + 1) + j)].cwiseAbs().maxCoeff());
      v_scale = std::max(v_scale, std::abs(P.value(r)));
    }
  const double tol = 1e-11 * std::max(g_scale, 1e-300) + 1e-14;
  v_scale = std::max(v_scale, 1e-300);
  std::vector<ShapeCriticalPoint> found;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
          for (int k = 0; k < 2; ++k) {
            const double v = g[static_cast<std::size_t>((i + a) * (n + 1) + j + b)](k);
            lo[k] = std::min(lo[k], v), hi[k] = std::max(hi[k], v);
          }
      // A component within round-off of 0 at a corner counts as a sign change
      // (the Lagrange top's ∂U/∂q3 ≡ 0, a pole where sin q2 is ±1e-16).
      const double zero = 1e-12 * g_scale;
      if (lo[0] > zero || hi[0] < -zero || lo[1] > zero || hi[1] < -zero) continue;
      ShapeCriticalPoint c{Vec2(-pi + (i + 0.5) * d, (j + 0.5) * d)};
      if (!newton(P, c.r, tol)) continue;
      canonicalise(P, c, tol, v_scale);
      c.residual = P.gradient(c.r).norm();
      const bool seen = std::any_of(found.begin(), found.end(), [&](const ShapeCriticalPoint& f) {
        return torus_distance(f.r, c.r) < 1e-6 || (f.degenerate && c.degenerate && std::abs(f.r(0) - c.r(0)) < 1e-6 &&
                                                   std::abs(P.value(f.r) - P.value(c.r)) <= 1e-10 * v_scale);
      });
      if (!seen) found.push_back(c);
    }
  std::sort(found.begin(), found.end(),
            [](const ShapeCriticalPoint& a, const ShapeCriticalPoint& b) { return a.r(0) != b.r(0) ? a.r(0) < b.r(0) : a.r(1) < b.r(1); });
  return found;
}

/// (g1, g2) → the class, as Grammel's on SO(3) (docs/atlas.md §3), with
/// roots μ = λ² within round-off of 0 counted as neutral.
EquilibriumStability stability_class(double g1, double g2) {
  const double scale = std::max(std::abs(g1), std::sqrt(std::abs(g2)));
  const double tol = 1e-7 * scale;
  const double D = g1 * g1 - 4.0 * g2;
  if (D < -tol * scale) return EquilibriumStability::complex_unstable;
  const double root = std::sqrt(std::max(D, 0.0));
  const double mu_plus = 0.5 * (-g1 + root), mu_minus = 0.5 * (-g1 - root);
  const int unstable = (mu_plus > tol ? 1 : 0) + (mu_minus > tol ? 1 : 0);
  return unstable == 0 ? EquilibriumStability::stable
                       : (unstable == 1 ? EquilibriumStability::singly_unstable : EquilibriumStability::doubly_unstable);
}

/// Fills the motion, the body's Γ and Π, (g1, g2), the classes and the flags.
/// False at a pole with massless rings (M singular: outside the Cardan system).
bool describe(const system::CardanTop& top, const ShapePotential& P, const ShapeCriticalPoint& c, CardanEquilibrium& e) {
  e.q = ShapePotential::config(c.r);
  P.motion(c.r, e.omega, e.l, e.h);
  e.degenerate = c.degenerate;
  e.pole = std::abs(std::sin(c.r(0))) < 1e-9;
  e.residual = c.residual;
  const Vec3 qdot(e.omega, 0.0, 0.0);
  const Mat3 M = top.mass_matrix(e.q);
  if (!(std::abs(M.determinant()) > 1e-12 * std::pow(M.norm(), 3))) return false;
  e.gamma = top.attitude(e.q).transpose() * Vec3::UnitZ();
  e.angular_momentum = top.J * (system::CardanTop::body_rate_matrix(e.q) * qdot);
  const system::TorusState x{e.q, M * qdot};
  const auto Df = top.field_jacobian(x);
  constexpr int idx[4] = {1, 2, 4, 5};  // q2, q3, p2, p3
  Eigen::Matrix4d A;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) A(i, j) = Df(idx[i], idx[j]);
  e.g1 = -0.5 * (A * A).trace();
  e.g2 = A.determinant();
  e.stability = stability_class(e.g1, e.g2);
  // Routh's amended potential at ℓ (whichever potential found the point).
  const ShapePotential U{top, true, e.l};
  const Eigen::SelfAdjointEigenSolver<Mat2> es(U.hessian(c.r));
  e.nonlinearly_stable = !c.degenerate && es.eigenvalues()(0) > 1e-9 * std::max(1.0, es.eigenvalues().cwiseAbs().maxCoeff());
  return true;
}

}  // namespace

double wrap_angle_signed(double a) {
  a = std::remainder(a, 2.0 * pi);
  return a <= -pi ? a + 2.0 * pi : a;
}

double wrap_angle_positive(double a) {
  a = std::fmod(a, 2.0 * pi);
  if (a < 0.0) a += 2.0 * pi;
  return a >= 2.0 * pi ? 0.0 : a;
}

void require_cyclic_outer_angle(const system::CardanTop& top, const std::string& file, const std::string& command) {
  if (!top.outer_angle_cyclic())
    throw InputError(file + ": [suspension] tilt: lgi " + command +
                     " on a Cardan top needs a vertical outer axis (tilt = 0, or no gravity), where the outer "
                     "angle is cyclic");
}

double cardan_amended_potential(const system::CardanTop& top, double l, double q2, double q3) {
  return ShapePotential{top, true, l}.value(Vec2(q2, q3));
}

std::vector<CardanEquilibrium> cardan_equilibria_at(const system::CardanTop& top, double l, int grid) {
  const ShapePotential P{top, true, l};
  std::vector<CardanEquilibrium> rows;
  for (const ShapeCriticalPoint& c : critical_points(P, grid)) {
    CardanEquilibrium e;
    if (!describe(top, P, c, e)) continue;
    e.branch = static_cast<int>(rows.size());
    rows.push_back(e);
  }
  return rows;
}

double default_cardan_omega_max(const system::CardanTop& top) {
  double gradient = 0.0, inertia = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 24; ++i)
    for (int j = 0; j < 24; ++j) {
      const Vec3 q(0.0, -pi + (i + 0.5) * pi / 12.0, (j + 0.5) * pi / 12.0);
      gradient = std::max(gradient, top.potential_gradient(q).norm());
      inertia = std::min(inertia, top.mass_matrix(q)(0, 0));
    }
  return gradient > 0.0 && inertia > 0.0 ? 3.0 * std::sqrt(gradient / inertia) : 3.0;
}

std::vector<CardanEquilibrium> cardan_equilibrium_branches(const system::CardanTop& top, int samples, double omega_max,
                                                            int grid,
                                                            const std::function<bool(std::size_t, std::size_t)>& sample_done) {
  const int n = samples + samples % 2;  // even: ω = 0 (where W_0 = V may be flat) is not sampled
  std::vector<CardanEquilibrium> rows, previous;
  int branches = 0;
  for (int k = 0; k < n; ++k) {
    const double omega = omega_max * (2.0 * (k + 0.5) / n - 1.0);
    const ShapePotential P{top, false, omega};
    std::vector<CardanEquilibrium> now;
    for (const ShapeCriticalPoint& c : critical_points(P, grid)) {
      CardanEquilibrium e;
      if (!describe(top, P, c, e)) continue;
      // Continuation: the nearest point of the previous ω (within 0.3 rad) gives the branch.
      double best = 0.3;
      e.branch = -1;
      if (k > 0 && std::signbit(omega) == std::signbit(previous.empty() ? omega : previous.front().omega))
        for (const CardanEquilibrium& p : previous)
          if (const double dist = torus_distance(Vec2(p.q(1), p.q(2)), Vec2(e.q(1), e.q(2))); dist < best)
            best = dist, e.branch = p.branch;
      if (e.branch < 0 || std::any_of(now.begin(), now.end(), [&](const auto& o) { return o.branch == e.branch; }))
        e.branch = branches++;
      now.push_back(e);
    }
    rows.insert(rows.end(), now.begin(), now.end());
    previous = std::move(now);
    if (sample_done && !sample_done(static_cast<std::size_t>(k + 1), static_cast<std::size_t>(n))) break;
  }
  std::stable_sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.branch < b.branch; });
  return rows;
}

double cardan_minimum_energy(const system::CardanTop& top, double l) {
  const ShapePotential P{top, true, l};
  double lowest = std::numeric_limits<double>::infinity();
  for (const ShapeCriticalPoint& c : critical_points(P, 96)) lowest = std::min(lowest, P.value(c.r));
  for (int i = 0; i < 256; ++i)
    for (int j = 0; j < 256; ++j)
      lowest = std::min(lowest, P.value(Vec2(-pi + (i + 0.5) * pi / 128.0, (j + 0.5) * pi / 128.0)));
  return lowest;
}

}  // namespace lgi::experiments

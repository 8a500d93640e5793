// The critical values of (H, K) on a leaf of the Kovalevskaya top (kovalevskaya_critical.hpp).
#include "experiments/analysis/kovalevskaya_critical.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace lgi::experiments {

namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;  // a point x = (Γ, Π) of the phase space

/// The gradients of H, k, C = Π·Γ and |Γ|² at x = (Γ, Π) in the scaled top
/// (J = diag(2, 2, 1), so Ω = (Π1/2, Π2/2, Π3); k as in kovalevskaya_k with c = ±1).
struct Gradients {
  Vec6 H, k, C, G;
};
Gradients gradients(const HeavyTopBody& b, const Vec6& x) {
  const double c = b.weight.x(), w1 = 0.5 * x(3), w2 = 0.5 * x(4);
  const double a = w1 * w1 - w2 * w2 - c * x(0), bb = 2.0 * w1 * w2 - c * x(1);
  Gradients g;
  g.H << b.weight, x(3) / b.J(0, 0), x(4) / b.J(1, 1), x(5) / b.J(2, 2);
  g.k << -2.0 * c * a, -2.0 * c * bb, 0.0, 2.0 * (a * w1 + bb * w2), 2.0 * (-a * w2 + bb * w1), 0.0;
  g.C << x.tail<3>(), x.head<3>();
  g.G << 2.0 * x.head<3>(), Vec3::Zero();
  return g;
}

// z = (x, α, β, γ), the Lagrange system's unknowns.
using Vec9 = Eigen::Matrix<double, 9, 1>;
using Mat9 = Eigen::Matrix<double, 9, 9>;

/// The Lagrange system F(x, α, β, γ) = (∇k − α∇H − β∇C − γ∇|Γ|², H − h, C − ℓ, |Γ|² − 1).
Vec9 lagrange_residual(const HeavyTopBody& b, const Vec9& z, double l, double h) {
  const Vec6 x = z.head<6>();
  const Gradients g = gradients(b, x);
  Vec9 F;
  F.head<6>() = g.k - z(6) * g.H - z(7) * g.C - z(8) * g.G;
  F(6) = heavy_top_energy(b, x) - h, F(7) = x.tail<3>().dot(x.head<3>()) - l, F(8) = x.head<3>().squaredNorm() - 1.0;
  return F;
}

/// Its Jacobian: the Hessian of k by central differences of the exact gradient (k is a
/// quartic; the step 1e-5 leaves an error ~1e-10), the others exactly.
Mat9 lagrange_jacobian(const HeavyTopBody& b, const Vec9& z) {
  const Vec6 x = z.head<6>();
  const Gradients g = gradients(b, x);
  Mat9 M = Mat9::Zero();
  constexpr double step = 1e-5;
  for (int i = 0; i < 6; ++i) {
    Vec6 p = x, m = x;
    p(i) += step, m(i) -= step;
    M.block<6, 1>(0, i) = (gradients(b, p).k - gradients(b, m).k) / (2.0 * step);
  }
  for (int i = 0; i < 3; ++i) {
    M(3 + i, 3 + i) -= z(6) / b.J(i, i);                         // α Hess H
    M(i, 3 + i) -= z(7), M(3 + i, i) -= z(7);                     // β Hess C
    M(i, i) -= 2.0 * z(8);                                         // γ Hess |Γ|²
  }
  M.block<6, 1>(0, 6) = -g.H, M.block<6, 1>(0, 7) = -g.C, M.block<6, 1>(0, 8) = -g.G;
  M.block<1, 6>(6, 0) = g.H.transpose(), M.block<1, 6>(7, 0) = g.C.transpose(), M.block<1, 6>(8, 0) = g.G.transpose();
  return M;
}

/// Newton's method with minimum-norm steps (the solutions at fixed h are curves, so
/// the Jacobian is singular there) from x with least-squares multipliers; true when
/// the residual falls below 1e-12.
bool solve_critical(const HeavyTopBody& b, double l, double h, Vec6& x) {
  const Gradients g0 = gradients(b, x);
  Eigen::Matrix<double, 6, 3> A;
  A << g0.H, g0.C, g0.G;
  Vec9 z;
  z << x, A.colPivHouseholderQr().solve(g0.k);
  for (int it = 0; it < 40; ++it) {
    const Vec9 F = lagrange_residual(b, z, l, h);
    if (F.lpNorm<Eigen::Infinity>() < 1e-12) {
      x = z.head<6>();
      return true;
    }
    // The complete orthogonal decomposition gives the minimum-norm least-squares step.
    Eigen::CompleteOrthogonalDecomposition<Mat9> cod;
    cod.setThreshold(1e-9);
    cod.compute(lagrange_jacobian(b, z));
    Vec9 d = cod.solve(-F);
    const double n = d.norm();
    if (!std::isfinite(n)) return false;
    if (n > 0.5) d *= 0.5 / n;  // a damped step far from a solution
    z += d;
  }
  return false;
}

}  // namespace

SecondIntegral kovalevskaya_integral(const HeavyTopBody& scaled) {
  return [scaled](const StateVec6& x) {
    IntegralValue q;
    q.value = kovalevskaya_k(scaled, KovalevskayaScale{1.0, 1.0}, x.head<3>(), x.tail<3>());
    q.gradient = gradients(scaled, x).k;
    return q;
  };
}

HeavyTopBody scaled_kovalevskaya(const HeavyTopBody& body) {
  HeavyTopBody b;
  b.J = Vec3(2.0, 2.0, 1.0).asDiagonal();
  b.weight = Vec3(body.weight.x() < 0.0 ? -1.0 : 1.0, 0.0, 0.0);
  return b;
}

double critical_rank_gap(const HeavyTopBody& scaled, const Vec3& gamma, const Vec3& Pi) {
  Vec6 x;
  x << gamma, Pi;
  const Gradients g = gradients(scaled, x);
  Eigen::Matrix<double, 4, 6> M;
  M << g.H.transpose(), g.k.transpose(), g.C.transpose(), g.G.transpose();
  const Eigen::Vector4d s = Eigen::JacobiSVD<Eigen::Matrix<double, 4, 6>>(M).singularValues();
  return s(0) > 0.0 ? s(3) / s(0) : 0.0;
}

int appelrot_piece(int family, double s, double h, double G) {
  if (family != 2) return 0;
  if (G == 0.0) return h < 0.0 ? 0 : 1;
  if (s < 0.0) return 0;
  return s * s * s < G ? 1 : 2;  // h̃ = s + G/(2s²) turns at s³ = G
}

std::vector<std::vector<CriticalValue>> kovalevskaya_critical_values(const HeavyTopBody& scaled, double l_scaled,
                                                                      const std::vector<double>& hs, int seeds,
                                                                      const std::function<bool()>& keep_going) {
  const double G = 0.5 * l_scaled * l_scaled;
  std::vector<std::vector<CriticalValue>> out;
  std::vector<Vec6> previous;  // the critical states at the previous h: continuation along the arcs
  for (const double h : hs) {
    if (keep_going && !keep_going()) break;
    std::vector<Vec6> starts = energy_surface_lattice(scaled, l_scaled, h, seeds);
    starts.insert(starts.end(), previous.begin(), previous.end());
    std::vector<CriticalValue> found;
    previous.clear();
    for (Vec6 x : starts) {
      if (!solve_critical(scaled, l_scaled, h, x)) continue;
      CriticalValue v;
      v.gamma = x.head<3>(), v.Pi = x.tail<3>(), v.h = h;
      v.k = kovalevskaya_k(scaled, KovalevskayaScale{1.0, 1.0}, v.gamma, v.Pi);
      v.rank_gap = critical_rank_gap(scaled, v.gamma, v.Pi);
      if (v.rank_gap > 1e-7) continue;
      const bool seen = std::any_of(found.begin(), found.end(),
                                    [&](const CriticalValue& w) { return std::abs(w.k - v.k) <= 1e-7 * (1.0 + v.k); });
      if (seen) continue;
      const AppelrotDistance d = appelrot_distance(l_scaled, h, v.k);
      if (d.distance <= 1e-6 * (1.0 + v.k)) v.family = d.family, v.piece = appelrot_piece(d.family, d.s, h, G);
      v.distance = d.distance;
      found.push_back(v);
      previous.push_back(x);
    }
    std::sort(found.begin(), found.end(), [](const CriticalValue& a, const CriticalValue& b) { return a.k < b.k; });
    out.push_back(found);
  }
  return out;
}

std::vector<int> appelrot_realised(const std::vector<AppelrotPoint>& curve, double l_scaled,
                                   const std::vector<double>& hs,
                                   const std::vector<std::vector<CriticalValue>>& critical) {
  const double G = 0.5 * l_scaled * l_scaled;
  auto has = [&](std::size_t i, int family, int piece) {
    return std::any_of(critical[i].begin(), critical[i].end(),
                       [&](const CriticalValue& v) { return v.family == family && v.piece == piece; });
  };
  std::vector<int> out;
  for (const AppelrotPoint& p : curve) {
    const int piece = appelrot_piece(p.family, p.s, p.h, G);
    const auto above = std::lower_bound(hs.begin(), hs.end(), p.h);
    int r = 0;
    if (above != hs.end()) {
      const auto i = static_cast<std::size_t>(above - hs.begin());
      const double tol = 1e-12 * (1.0 + std::abs(p.h));
      if (std::abs(*above - p.h) <= tol) r = has(i, p.family, piece);
      else if (i > 0) r = has(i - 1, p.family, piece) && has(i, p.family, piece);
    }
    out.push_back(r);
  }
  return out;
}

}  // namespace lgi::experiments

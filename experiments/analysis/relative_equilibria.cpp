// Relative equilibria of the heavy top (relative_equilibria.hpp; docs/atlas.md §2–§3).
#include "experiments/analysis/relative_equilibria.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "lie/so3.hpp"

namespace lgi::experiments {

namespace {

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec5 = Eigen::Matrix<double, 5, 1>;
using Mat5 = Eigen::Matrix<double, 5, 5>;

/// The body in its principal frame: body vectors are P · (principal-frame vectors).
struct Principal {
  Vec3 A, w;
  Mat3 P = Mat3::Identity();
};

Principal principal_frame(const HeavyTopBody& body) {
  Principal f;
  const Mat3& J = body.J;
  const bool diagonal = J(0, 1) == 0.0 && J(0, 2) == 0.0 && J(1, 2) == 0.0 && J(1, 0) == 0.0 && J(2, 0) == 0.0 &&
                        J(2, 1) == 0.0;
  if (diagonal) {  // no rotation: exact for the usual scenes
    f.A = J.diagonal();
  } else {
    const Eigen::SelfAdjointEigenSolver<Mat3> eig(J);
    f.A = eig.eigenvalues();
    f.P = eig.eigenvectors();
    if (f.P.determinant() < 0.0) f.P.col(2) *= -1.0;
  }
  f.w = f.P.transpose() * body.weight;
  return f;
}

/// One branch: regular (ν in (a, b), sign of ω) or degenerate (ν = −A_axis, Γ_axis of one sign).
struct Branch {
  int id = 0;
  bool regular = true;
  double a = 0.0, b = 0.0;  // ν interval (±inf allowed)
  int sigma = 1;            // sign of ω
  int axis = -1;            // degenerate: the free component
  int pair = -1;            // degenerate: a second free component (A equal, χ zero there), set to 0
  int axis_sign = 1;        // degenerate: sign of Γ_axis
  double omega_min = 0.0;   // degenerate: the family exists for |ω| ≥ omega_min
  double scale = 1.0;       // ν or ω scale for the sampling map
  std::string kind, label;  // label: its asymptotic ends (EquilibriumBranch)
};

struct Point {
  double omega = 0.0;
  Vec3 gamma = Vec3::Zero();  // principal frame
  bool valid = false;
};

/// τ ∈ (0, 1) → a point of the branch; the map clusters samples at the ends
/// (poles, where ω → ∞, and ν → ±∞, where ω → 0).
Point point_on(const Principal& f, const Branch& br, double tau) {
  Point p;
  if (br.regular) {
    double nu;
    if (std::isinf(br.a) && std::isinf(br.b)) nu = br.scale * std::tan(std::numbers::pi * (tau - 0.5));
    else if (std::isinf(br.a)) nu = br.b - br.scale * std::pow(std::tan(0.5 * std::numbers::pi * (1.0 - tau)), 2);
    else if (std::isinf(br.b)) nu = br.a + br.scale * std::pow(std::tan(0.5 * std::numbers::pi * tau), 2);
    else nu = br.a + (br.b - br.a) * tau * tau * (3.0 - 2.0 * tau);  // smoothstep: clustered at both poles
    Vec3 v;
    for (int i = 0; i < 3; ++i) v[i] = f.w[i] == 0.0 ? 0.0 : f.w[i] / (f.A[i] + nu);
    const double s = v.norm();
    if (!(s > 0.0) || !std::isfinite(s)) return p;
    p.gamma = v / s;
    p.omega = br.sigma * std::sqrt(s);
    p.valid = true;
    return p;
  }
  // Degenerate: ω² from omega_min² (τ → 1) to ∞ (τ → 0).
  const double om2 = br.omega_min > 0.0 ? br.omega_min * br.omega_min / tau
                                        : std::pow(br.scale * (1.0 - tau) / tau, 2);
  const double Ai = f.A[br.axis];
  double rest = 0.0;
  for (int j = 0; j < 3; ++j) {
    if (j == br.axis || j == br.pair) continue;
    p.gamma[j] = f.w[j] == 0.0 ? 0.0 : f.w[j] / (om2 * (f.A[j] - Ai));
    rest += p.gamma[j] * p.gamma[j];
  }
  if (rest > 1.0) return p;
  p.gamma[br.axis] = br.axis_sign * std::sqrt(1.0 - rest);
  p.omega = br.sigma * std::sqrt(om2);
  p.valid = std::isfinite(p.omega);
  return p;
}

/// Where a regular branch goes as ν tends to an end of its interval (docs/atlas.md §2):
/// ν → −∞ is ω → 0 with Γ → −χ/|χ| (hanging), ν → +∞ is Γ → +χ/|χ| (upright), and a
/// pole ν → −A_i is ω → ∞ with Γ → ±e_i, the sign of w_i/(A_i + ν).
std::string end_label(const Principal& f, double nu, bool from_above) {
  if (std::isinf(nu)) return nu < 0.0 ? "hanging" : "upright";
  std::string out;
  for (int i = 0; i < 3; ++i) {
    if (f.w[i] == 0.0 || f.A[i] != -nu) continue;
    const bool plus = (f.w[i] > 0.0) == from_above;
    out += std::string(out.empty() ? "" : "/") + (plus ? "+e" : "-e") + std::to_string(i + 1);
  }
  return out;
}

std::vector<Branch> make_branches(const Principal& f) {
  std::vector<Branch> out;
  const double scale = std::max({f.A[0], f.A[1], f.A[2]});
  std::vector<double> poles;
  for (int i = 0; i < 3; ++i)
    if (f.w[i] != 0.0) poles.push_back(-f.A[i]);
  std::sort(poles.begin(), poles.end());
  poles.erase(std::unique(poles.begin(), poles.end()), poles.end());
  if (f.w.norm() > 0.0) {
    std::vector<double> ends = {-INFINITY};
    ends.insert(ends.end(), poles.begin(), poles.end());
    ends.push_back(INFINITY);
    for (std::size_t k = 0; k + 1 < ends.size(); ++k)
      for (int sigma : {1, -1}) {
        Branch b;
        b.a = ends[k], b.b = ends[k + 1], b.sigma = sigma, b.scale = scale;
        b.kind = "regular, nu in (" + std::to_string(b.a) + ", " + std::to_string(b.b) + "), omega " +
                 (sigma > 0 ? "> 0" : "< 0");
        b.label = end_label(f, b.a, true) + " - " + end_label(f, b.b, false);
        out.push_back(b);
      }
  }
  for (int i = 0; i < 3; ++i) {
    if (f.w[i] != 0.0) continue;
    // A second axis with the same moment: a free pair (a circle of solutions) if χ is zero
    // there too (represented by Γ_pair = 0), no solution otherwise.
    int pair = -1;
    bool none = false, duplicate = false;
    for (int j = 0; j < 3; ++j) {
      if (j == i || f.A[j] != f.A[i]) continue;
      if (f.w[j] != 0.0) none = true;
      else if (j < i) duplicate = true;
      else pair = j;
    }
    if (none || duplicate) continue;
    double om4 = 0.0;
    for (int j = 0; j < 3; ++j)
      if (j != i && j != pair && f.w[j] != 0.0) om4 += std::pow(f.w[j] / (f.A[j] - f.A[i]), 2);
    for (int sign : {1, -1})
      for (int sigma : {1, -1}) {
        Branch b;
        b.regular = false, b.axis = i, b.pair = pair, b.axis_sign = sign, b.sigma = sigma;
        b.omega_min = std::sqrt(std::sqrt(om4)), b.scale = 1.0;
        b.kind = std::string(f.w.norm() > 0.0 ? "degenerate (Gamma_" : "principal axis (Gamma_") +
                 std::to_string(i + 1) + (sign > 0 ? " > 0" : " < 0") + "), omega " + (sigma > 0 ? "> 0" : "< 0");
        b.label = (sign > 0 ? "+e" : "-e") + std::to_string(i + 1);
        out.push_back(b);
      }
  }
  for (std::size_t k = 0; k < out.size(); ++k) out[k].id = static_cast<int>(k);
  return out;
}

double l_of(const Principal& f, const Point& p) { return p.omega * p.gamma.dot(f.A.cwiseProduct(p.gamma)); }

RelativeEquilibrium to_body(const Principal& f, const Point& p, int branch) {
  RelativeEquilibrium e;
  e.omega = p.omega;
  e.gamma = f.P * p.gamma;
  const Vec3 AG = f.A.cwiseProduct(p.gamma);
  e.angular_momentum = f.P * (p.omega * AG);
  e.l = p.omega * p.gamma.dot(AG);
  e.h = 0.5 * p.omega * p.omega * p.gamma.dot(AG) + f.w.dot(p.gamma);
  e.branch = branch;
  return e;
}

/// Newton's method on (ω²A∘Γ + μΓ − w, Γ·Γ − 1, ωΓ·(A∘Γ) − l) in (Γ, ω, μ).
Point polish(const Principal& f, Point p, double l) {
  Vec5 x;
  const Vec3 AG0 = f.A.cwiseProduct(p.gamma);
  x << p.gamma, p.omega, (f.w - p.omega * p.omega * AG0).dot(p.gamma);
  auto residual = [&](const Vec5& y) {
    const Vec3 G = y.head<3>();
    const Vec3 AG = f.A.cwiseProduct(G);
    Vec5 F;
    F.head<3>() = y[3] * y[3] * AG + y[4] * G - f.w;
    F[3] = G.dot(G) - 1.0;
    F[4] = y[3] * G.dot(AG) - l;
    return F;
  };
  Vec5 F = residual(x);
  for (int it = 0; it < 12; ++it) {
    const Vec3 G = x.head<3>();
    const Vec3 AG = f.A.cwiseProduct(G);
    Mat5 D = Mat5::Zero();
    D.topLeftCorner<3, 3>() = (x[3] * x[3] * f.A).asDiagonal();
    D.topLeftCorner<3, 3>() += x[4] * Mat3::Identity();
    D.block<3, 1>(0, 3) = 2.0 * x[3] * AG;
    D.block<3, 1>(0, 4) = G;
    D.block<1, 3>(3, 0) = 2.0 * G.transpose();
    D.block<1, 3>(4, 0) = 2.0 * x[3] * AG.transpose();
    D(4, 3) = G.dot(AG);
    const Vec5 step = D.fullPivLu().solve(-F);
    const Vec5 y = x + step;
    const Vec5 Fy = residual(y);
    if (!(Fy.norm() < F.norm()) && it > 0) break;
    x = y, F = Fy;
    if (step.norm() <= 1e-16 * std::max(1.0, x.norm())) break;
  }
  p.gamma = x.head<3>();
  p.omega = x[3];
  return p;
}

bool same_equilibrium(const RelativeEquilibrium& a, const RelativeEquilibrium& b) {
  const double scale = 1.0 + std::abs(a.omega);
  return (a.gamma - b.gamma).norm() < 1e-9 && std::abs(a.omega - b.omega) < 1e-9 * scale;
}

constexpr int search_samples = 4000;

}  // namespace

const char* stability_name(EquilibriumStability s) {
  switch (s) {
    case EquilibriumStability::stable: return "stable";
    case EquilibriumStability::singly_unstable: return "singly unstable";
    case EquilibriumStability::doubly_unstable: return "doubly unstable";
    case EquilibriumStability::complex_unstable: return "complex unstable";
  }
  return "?";
}

void classify(const HeavyTopBody& body, RelativeEquilibrium& e) {
  const Mat3 Jinv = body.J.inverse();
  const Vec3 Omega = e.omega * e.gamma;
  Mat6 M;
  M.topLeftCorner<3, 3>() = lie::hat(e.angular_momentum) * Jinv - lie::hat(Omega);
  M.topRightCorner<3, 3>() = -lie::hat(body.weight);
  M.bottomLeftCorner<3, 3>() = lie::hat(e.gamma) * Jinv;
  M.bottomRightCorner<3, 3>() = -lie::hat(Omega);
  const Mat6 M2 = M * M;
  const double t2 = M2.trace(), t4 = (M2 * M2).trace();
  e.g1 = -0.5 * t2;
  e.g2 = t2 * t2 / 8.0 - t4 / 4.0;
  // A root λ² = 0 (a symmetry's neutral pair: the Lagrange top's carrousels) comes out as g2 of
  // either sign at round-off (e.g. −2.3e-13 against g1² = 1.1e3): within 1e-12 g1² it counts as 0.
  const double g2 = std::abs(e.g2) <= 1e-12 * e.g1 * e.g1 ? 0.0 : e.g2;
  if (g2 < 0.0) e.stability = EquilibriumStability::singly_unstable;
  else if (e.g1 * e.g1 < 4.0 * g2) e.stability = EquilibriumStability::complex_unstable;
  else if (e.g1 > 0.0) e.stability = EquilibriumStability::stable;
  else e.stability = EquilibriumStability::doubly_unstable;
  // Energy–Casimir: the Hessian of U_l on the sphere's tangent plane at Γ is positive definite.
  const Vec3& g = e.gamma;
  const Vec3 Jg = body.J * g;
  const double q = g.dot(Jg), l2 = e.l * e.l;
  const Vec3 grad = -l2 / (q * q) * Jg + body.weight;
  const Mat3 hess = -l2 / (q * q) * body.J + 4.0 * l2 / (q * q * q) * Jg * Jg.transpose();
  const Vec3 t1 = g.unitOrthogonal(), t2v = g.cross(t1);
  Eigen::Matrix<double, 3, 2> T;
  T << t1, t2v;
  const Eigen::Matrix2d H = T.transpose() * (hess - g.dot(grad) * Mat3::Identity()) * T;
  e.nonlinearly_stable = H(0, 0) > 0.0 && H.determinant() > 0.0;
  e.residual = (e.omega * e.omega * Jg.cross(g) + g.cross(body.weight)).norm();
}

EquilibriumSet equilibria_at(const HeavyTopBody& body, double l) {
  const Principal f = principal_frame(body);
  EquilibriumSet out;
  const std::vector<Branch> branches = make_branches(f);
  for (const Branch& br : branches) {
    out.branches.push_back({br.id, br.kind, br.label});
    Point prev;
    double prev_tau = 0.0, prev_f = 0.0;
    for (int k = 1; k < search_samples; ++k) {
      const double tau = static_cast<double>(k) / search_samples;
      const Point p = point_on(f, br, tau);
      if (!p.valid) {
        prev = p;
        continue;
      }
      const double fk = l_of(f, p) - l;
      if (prev.valid && (fk == 0.0 || (prev_f < 0.0) != (fk < 0.0))) {
        double lo = prev_tau, hi = tau, flo = prev_f;
        for (int it = 0; it < 200 && fk != 0.0; ++it) {  // bisection to round-off in τ
          const double mid = 0.5 * (lo + hi);
          if (mid <= lo || mid >= hi) break;
          const Point pm = point_on(f, br, mid);
          if (!pm.valid) break;
          const double fm = l_of(f, pm) - l;
          if ((fm < 0.0) == (flo < 0.0) && fm != 0.0) lo = mid, flo = fm;
          else hi = mid;
        }
        RelativeEquilibrium e = to_body(f, polish(f, point_on(f, br, fk == 0.0 ? tau : hi), l), br.id);
        classify(body, e);
        const bool seen = std::any_of(out.rows.begin(), out.rows.end(),
                                      [&](const RelativeEquilibrium& r) { return same_equilibrium(r, e); });
        if (!seen) out.rows.push_back(e);
      }
      prev = p, prev_tau = tau, prev_f = fk;
    }
  }
  if (l == 0.0 && body.weight.norm() > 0.0) {  // the static equilibria (ω = 0): hanging and upright
    for (double sign : {1.0, -1.0}) {
      RelativeEquilibrium e;
      e.gamma = sign * body.weight.normalized();
      e.h = body.weight.dot(e.gamma);
      e.branch = -1;
      classify(body, e);
      out.rows.push_back(e);
    }
  }
  std::sort(out.rows.begin(), out.rows.end(), [](const auto& a, const auto& b) {
    return a.h != b.h ? a.h < b.h : a.branch < b.branch;
  });
  return out;
}

namespace {

/// The point between samples τ_lo and τ_hi (classes differ) where Grammel's class changes:
/// bisection on the class to round-off in τ; the row is the first point of the far side.
RelativeEquilibrium class_change(const HeavyTopBody& body, const Principal& f, const Branch& br, double lo, double hi,
                                 EquilibriumStability at_lo) {
  RelativeEquilibrium far = to_body(f, point_on(f, br, hi), br.id);
  classify(body, far);
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    const Point p = point_on(f, br, mid);
    if (!p.valid) break;
    RelativeEquilibrium e = to_body(f, p, br.id);
    classify(body, e);
    if (e.stability == at_lo) lo = mid;
    else hi = mid, far = e;
  }
  far.class_change = true;
  return far;
}

}  // namespace

EquilibriumSet equilibrium_branches(const HeavyTopBody& body, int samples,
                                    const std::function<bool(std::size_t, std::size_t)>& branch_done) {
  const Principal f = principal_frame(body);
  EquilibriumSet out;
  const auto branches = make_branches(f);
  // Within a branch too, every 2^16 samples (up to 10^7 a branch: seconds): the branches done so far.
  const auto stopped_within = [&](std::size_t k) {
    return branch_done && k % (std::size_t{1} << 16) == 0 && !branch_done(out.branches.size() - 1, branches.size());
  };
  for (const Branch& br : branches) {
    out.branches.push_back({br.id, br.kind, br.label});
    std::vector<double> taus, ls;
    std::vector<Point> pts;
    for (int k = 1; k < samples; ++k) {
      if (stopped_within(static_cast<std::size_t>(k))) return out;
      const double tau = static_cast<double>(k) / samples;
      const Point p = point_on(f, br, tau);
      if (!p.valid) continue;
      taus.push_back(tau), pts.push_back(p), ls.push_back(l_of(f, p));
    }
    EquilibriumStability prev_class = EquilibriumStability::stable;
    for (std::size_t k = 0; k < pts.size(); ++k) {
      if (stopped_within(k + 1)) return out;
      RelativeEquilibrium e = to_body(f, pts[k], br.id);
      classify(body, e);
      if (k > 0 && prev_class != e.stability)
        out.rows.push_back(class_change(body, f, br, taus[k - 1], taus[k], prev_class));
      prev_class = e.stability;
      out.rows.push_back(e);
      if (k == 0 || k + 1 >= pts.size() || (ls[k] - ls[k - 1]) * (ls[k + 1] - ls[k]) >= 0.0) continue;
      // A turning point of ℓ between the neighbours: golden-section search for the extremum.
      const double sgn = ls[k] > ls[k - 1] ? -1.0 : 1.0;  // minimise sgn·ℓ
      double a = taus[k - 1], b = taus[k + 1];
      const double r = 0.5 * (std::sqrt(5.0) - 1.0);
      for (int it = 0; it < 200 && b - a > 1e-16; ++it) {
        const double c = b - r * (b - a), d = a + r * (b - a);
        if (sgn * l_of(f, point_on(f, br, c)) < sgn * l_of(f, point_on(f, br, d))) b = d;
        else a = c;
      }
      RelativeEquilibrium fold = to_body(f, point_on(f, br, 0.5 * (a + b)), br.id);
      fold.fold = true;
      classify(body, fold);
      out.rows.push_back(fold);
    }
    if (branch_done && !branch_done(out.branches.size(), branches.size())) break;
  }
  return out;
}

}  // namespace lgi::experiments

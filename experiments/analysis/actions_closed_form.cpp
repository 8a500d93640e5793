// The actions of the Lagrange and Euler tops in closed form (docs/actions.md
// §1 and §2, where every formula below is derived).
#include <algorithm>
#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/ellint_3.hpp>
#include <boost/math/special_functions/ellint_rd.hpp>
#include <boost/math/special_functions/ellint_rf.hpp>
#include <boost/math/special_functions/ellint_rj.hpp>
#include <cmath>
#include <numbers>

#include "experiments/analysis/actions.hpp"

namespace lgi::experiments {
namespace {

using std::numbers::pi;

/// f(u) = u̇² = c3 u³ + c2 u² + c1 u + c0 (docs/actions.md §1).
struct Cubic {
  double c3 = 0.0, c2 = 0.0, c1 = 0.0, c0 = 0.0;
  double operator()(double u) const { return ((c3 * u + c2) * u + c1) * u + c0; }
  double derivative(double u) const { return (3.0 * c3 * u + 2.0 * c2) * u + c1; }
};

/// The smallest v in [0, b] with g(v) > 0 on (v, b], for g(0) ≤ 0 < g(b), by bisection to
/// adjacent doubles; the invariant g(a) ≤ 0 < g(b) is kept, and a is returned, so a root at
/// v = 0 exactly (g(0) = 0, a torus through a pole) is returned as 0.
template <class G>
double root_from_zero(const G& g, double b) {
  double a = 0.0;
  for (int i = 0; i < 2200; ++i) {
    const double m = 0.5 * (a + b);
    if (m <= a || m >= b) break;
    if (g(m) > 0.0) b = m;
    else a = m;
  }
  return a;
}

/// The Lagrange top with w > 0 (w < 0 is mapped to it by u → −u, L3 → −L3).
/// The turning points are kept as their distances d1 = 1 + u1 and d2 = 1 − u2 from the poles,
/// found from f written about each pole (docs/actions.md §1), so that on the lines ℓ = ±L3,
/// where f(∓1) = −(ℓ ± L3)²/A² vanishes and the torus passes through the hanging or upright
/// position, the pole is the turning point exactly, and near them d1, d2 keep their digits.
struct Reduced {
  LagrangeBody body;
  double l = 0.0, L3 = 0.0, h = 0.0;
  double sign = 1.0;  // −1 where the body was reflected
  Cubic f;
  double u1 = 0.0, u2 = 0.0, u3 = 0.0;
  double d1 = 0.0, d2 = 0.0;  // 1 + u1, 1 − u2
};

std::optional<Reduced> reduce(const LagrangeBody& b, double l, double L3, double h) {
  if (!(b.A > 0.0) || !(b.C > 0.0) || b.w == 0.0 || !std::isfinite(l + L3 + h)) return std::nullopt;
  Reduced r;
  r.sign = b.w > 0.0 ? 1.0 : -1.0;
  r.body = {b.A, b.C, std::abs(b.w)};
  r.l = l;
  r.L3 = r.sign * L3;
  r.h = h;
  const double A = b.A, w = r.body.w, hp = h - L3 * L3 / (2.0 * b.C), Ls = r.L3;
  // f(u) = (2/A)(h' − w u)(1 − u²) − (ℓ − L3 u)²/A², h' = h − L3²/(2C).
  r.f = {2.0 * w / A, -2.0 * hp / A - Ls * Ls / (A * A), -2.0 * w / A + 2.0 * l * Ls / (A * A),
         2.0 * hp / A - l * l / (A * A)};
  const double disc = r.f.c2 * r.f.c2 - 3.0 * r.f.c3 * r.f.c1;
  if (!(disc > 0.0)) return std::nullopt;
  const double uc = (-r.f.c2 - std::sqrt(disc)) / (3.0 * r.f.c3);  // the local maximum of f
  if (!(uc > -1.0 && uc < 1.0) || !(r.f(uc) > 0.0)) return std::nullopt;
  // f about the poles: f(−1 + v) = (2/A)(h' + w − w v)(2v − v²) − (ℓ + L3 − L3 v)²/A²,
  //                    f(1 − v)  = (2/A)(h' − w + w v)(2v − v²) − (ℓ − L3 + L3 v)²/A².
  const double em = l + Ls, ep = l - Ls;
  const auto below = [&](double v) {
    return (2.0 / A) * (hp + w - w * v) * v * (2.0 - v) - (em - Ls * v) * (em - Ls * v) / (A * A);
  };
  const auto above = [&](double v) {
    return (2.0 / A) * (hp - w + w * v) * v * (2.0 - v) - (ep + Ls * v) * (ep + Ls * v) / (A * A);
  };
  r.d1 = root_from_zero(below, 1.0 + uc);
  r.d2 = root_from_zero(above, 1.0 - uc);
  r.u1 = r.d1 - 1.0;
  r.u2 = 1.0 - r.d2;
  r.u3 = -r.f.c2 / r.f.c3 - r.u1 - r.u2;  // Vieta, then Newton
  for (int i = 0; i < 3; ++i) {
    const double d = r.f.derivative(r.u3);
    if (d != 0.0) r.u3 -= r.f(r.u3) / d;
  }
  if (!(r.u2 > r.u1) || !(r.u3 >= r.u2)) return std::nullopt;
  return r;
}

/// Π(n, k) = R_F(0, k'², 1) + (n/3) R_J(0, k'², 1, 1 − n) (DLMF 19.25.2), with 1 − n and
/// k'² = 1 − k² given directly: near n = 1 (a torus passing close to a pole) 1 − n keeps its
/// digits where n itself would round to 1.
double ellint_3_carlson(double kc2, double n, double one_minus_n) {
  return boost::math::ellint_rf(0.0, kc2, 1.0) + n / 3.0 * boost::math::ellint_rj(0.0, kc2, 1.0, one_minus_n);
}

}  // namespace

std::optional<LagrangeActions> lagrange_actions(const LagrangeBody& body, double l, double L3, double h) {
  const auto r = reduce(body, l, L3, h);
  if (!r) return std::nullopt;
  const double A = body.A, C = body.C, c3 = r->f.c3;
  const double u1 = r->u1, u2 = r->u2, u3 = r->u3, Ls = r->L3, d1 = r->d1, d2 = r->d2;
  // Carlson's forms with k² = (u2 − u1)/(u3 − u1) and k'² = (u3 − u2)/(u3 − u1) taken apart
  // (DLMF 19.25.1): K = R_F(0, k'², 1), K − E = (k²/3) R_D(0, k'², 1).
  const double k2 = (u2 - u1) / (u3 - u1), kc2 = (u3 - u2) / (u3 - u1);
  // u3 = u2: the orbit approaches u2 asymptotically (a separatrix, e.g. ℓ = L3 = 0 at h = w, the
  // pendulum's homoclinic orbit to the upright position); K and the period diverge, no torus.
  if (!(kc2 > 0.0)) return std::nullopt;
  const double K = boost::math::ellint_rf(0.0, kc2, 1.0), K_minus_E = k2 / 3.0 * boost::math::ellint_rd(0.0, kc2, 1.0);
  const double scale = 2.0 / std::sqrt(c3 * (u3 - u1));
  // J0 = ∫du/√f, J1 = ∫u du/√f, Jm = ∫du/((1−u)√f), Jp = ∫du/((1+u)√f) over [u1, u2].
  const double J0 = scale * K;
  const double J1 = scale * (u1 * K + (u3 - u1) * K_minus_E);
  const double am = (l - Ls) * (l - Ls), ap = (l + Ls) * (l + Ls);
  // On ℓ = ±L3 the torus passes through a pole (d2 = 0 or d1 = 0) and (ℓ ∓ L3)² = 0: the term
  // of the centrifugal potential singular there has a zero coefficient and is left out (the
  // rest, (ℓ − L3u)²/(1 − u²) = −L3² + 2L3²/(1 ∓ u), is finite at that pole). Off these lines
  // 1 − n− = d2/(1 − u1) and 1 − n+ = (1 + u2)/d1 are formed without cancellation.
  if ((am != 0.0 && !(d2 > 0.0)) || (ap != 0.0 && !(d1 > 0.0))) return std::nullopt;
  const double Jm = am == 0.0 ? 0.0 : scale * ellint_3_carlson(kc2, (u2 - u1) / (2.0 - d1), d2 / (2.0 - d1)) / (2.0 - d1);
  const double Jp = ap == 0.0 ? 0.0 : scale * ellint_3_carlson(kc2, -(u2 - u1) / d1, (2.0 - d2) / d1) / d1;
  const double hp = h - L3 * L3 / (2.0 * C);
  const double I_theta =
      (A / pi) * ((2.0 * hp / A + Ls * Ls / (A * A)) * J0 - c3 * J1 - am / (2.0 * A * A) * Jm - ap / (2.0 * A * A) * Jp);
  // Derivatives of I_θ (docs/actions.md §1): ∂h = J0/π, ∂ℓ and ∂L3 from the same integrals.
  const double dI_dh = J0 / pi;
  const double dI_dl = -((l - Ls) / 2.0 * Jm + (l + Ls) / 2.0 * Jp) / (pi * A);
  const double dI_dL3 = ((Ls - A * Ls / C) * J0 + (l - Ls) / 2.0 * Jm - (l + Ls) / 2.0 * Jp) / (pi * A);
  LagrangeActions a;
  a.actions = {l, L3, I_theta};
  a.frequencies = {-dI_dl / dI_dh, -r->sign * dI_dL3 / dI_dh, 1.0 / dI_dh};
  a.period = 2.0 * J0;
  a.u1 = r->sign > 0.0 ? u1 : -u2;
  a.u2 = r->sign > 0.0 ? u2 : -u1;
  a.u3 = r->sign * u3;
  return a;
}

double lagrange_nutation_action_quadrature(const LagrangeBody& body, double l, double L3, double h, int nodes) {
  const auto r = reduce(body, l, L3, h);
  if (!r || nodes < 1) return std::nan("");
  // u = u1 + (u2 − u1) sin²α: √f du = 2√c3 (u2 − u1)² sin²α cos²α √(u3 − u) dα; the integrand is
  // even and π-periodic in α, so the midpoint rule on [0, π/2] converges geometrically.
  const double d = r->u2 - r->u1, step = 0.5 * pi / nodes;
  double sum = 0.0;
  for (int i = 0; i < nodes; ++i) {
    const double a = (i + 0.5) * step, s = std::sin(a), c = std::cos(a);
    const double u = r->u1 + d * s * s;
    sum += s * s * c * c * std::sqrt(r->u3 - u) / (1.0 - u * u);
  }
  return (body.A / pi) * 2.0 * std::sqrt(r->f.c3) * d * d * sum * step;
}

std::optional<LagrangeBody> lagrange_body(const HeavyTopBody& b) {
  const Mat3& J = b.J;
  const double off = J(0, 1) * J(0, 1) + J(0, 2) * J(0, 2) + J(1, 2) * J(1, 2);
  if (off > 1e-24 * J.squaredNorm()) return std::nullopt;
  if (std::abs(J(0, 0) - J(1, 1)) > 1e-12 * J(0, 0)) return std::nullopt;
  if (b.weight.x() != 0.0 || b.weight.y() != 0.0 || b.weight.z() == 0.0) return std::nullopt;
  return LagrangeBody{J(0, 0), J(2, 2), b.weight.z()};
}

std::optional<EulerActions> euler_actions_at(const Vec3& moments, double l, double G, double h) {
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&](int i, int j) { return moments[i] < moments[j]; });
  const double small = moments[order[0]], mid = moments[order[1]], large = moments[order[2]];
  if (!(small < mid && mid < large) || !(G > 0.0) || !(h > 0.0)) return std::nullopt;
  const double delta = G * G - 2.0 * h * mid;  // > 0: about the largest axis; < 0: the smallest
  if (delta == 0.0 || G * G > 2.0 * h * large || G * G < 2.0 * h * small) return std::nullopt;
  const bool about_largest = delta > 0.0;
  // The working frame: axis 3 is the one circulated about (docs/actions.md §2).
  const double I1 = about_largest ? small : large, I2 = mid, I3 = about_largest ? large : small;
  const double I21 = I2 - I1, I31 = I3 - I1, I32 = I3 - I2;
  const double C13 = 2.0 * h * I3 - G * G, C31 = G * G - 2.0 * h * I1;
  const double lambda = std::sqrt(I32 * C31 / (I1 * I2 * I3));
  const double k = std::sqrt(std::max(0.0, I21 * C13 / (I32 * C31)));
  const double n = -I3 * I21 / (I1 * I32);
  if (!(k < 1.0)) return std::nullopt;
  const double K = boost::math::ellint_1(k), Pn = boost::math::ellint_3(k, n);
  const double period = 4.0 * K / lambda;
  const double I_circ = 2.0 / (pi * lambda * I3) * std::abs(G * G * (I31 / I1) * Pn - C13 * K);
  const double omega_g = G / I3 + G * I31 * Pn / (I1 * I3 * K);  // mean precession of the working axis 3 about m
  EulerActions a;
  a.period = period;
  a.pole = order[2];
  a.around = about_largest ? order[2] : order[0];
  const double omega_l = -2.0 * pi / period;
  if (about_largest) {
    a.actions = {l, G, I_circ};
    a.frequencies = {0.0, omega_g, omega_l};
  } else {  // the cap about the smallest axis, seen from the largest axis' chart: I = G − I_circ
    a.actions = {l, G, G - I_circ};
    a.frequencies = {0.0, omega_g + 2.0 * pi / period, omega_l};
  }
  return a;
}

std::optional<EulerActions> euler_actions(const Vec3& moments, const Vec3& Pi, double l) {
  const double G = Pi.norm();
  const double h = 0.5 * (Pi.array().square() / moments.array()).sum();
  return euler_actions_at(moments, l, G, h);
}

}  // namespace lgi::experiments

namespace lgi::experiments {

std::vector<LagrangeActions> lagrange_surface(const LagrangeBody& body, double h, int n,
                                              const std::function<bool()>& keep_going) {
  std::vector<LagrangeActions> rows;
  const double L = std::sqrt(2.0 * std::max(body.A, body.C) * (h + std::abs(body.w)));
  // An odd number of nodes, symmetric in sign bit for bit (node N−1−i is −node i): the lines
  // ℓ = ±L3, the tori through the hanging and the upright position, are hit exactly and not at a
  // round-off distance, and ℓ = L3 = 0 (the apex of the surface, where both lines meet) is a node.
  const int N = std::max(3, n % 2 == 0 ? n + 1 : n);
  for (int i = 0; i < N && (!keep_going || keep_going()); ++i)
    for (int j = 0; j < N; ++j) {
      const double l = L * (2 * i - (N - 1)) / (N - 1), L3 = L * (2 * j - (N - 1)) / (N - 1);
      if (const auto a = lagrange_actions(body, l, L3, h)) rows.push_back(*a);
    }
  return rows;
}

std::vector<EulerActions> euler_surface(const Vec3& moments, double h, int n,
                                        const std::function<bool()>& keep_going) {
  std::vector<EulerActions> rows;
  const double G_min = std::sqrt(2.0 * h * moments.minCoeff()), G_max = std::sqrt(2.0 * h * moments.maxCoeff());
  for (int i = 0; i < n && (!keep_going || keep_going()); ++i)
    for (int j = 0; j < n; ++j) {
      // Open intervals: the steady rotations (G at either end) have no 1-torus in Π.
      const double G = G_min + (G_max - G_min) * (i + 0.5) / n;
      const double l = n > 1 ? -G + 2.0 * G * j / (n - 1) : 0.0;
      if (const auto a = euler_actions_at(moments, l, G, h)) rows.push_back(*a);
    }
  return rows;
}

}  // namespace lgi::experiments

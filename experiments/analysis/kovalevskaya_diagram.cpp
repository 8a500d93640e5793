// The Kovalevskaya top's (h, k) diagram (kovalevskaya_diagram.hpp; docs/atlas.md §9).
#include "experiments/analysis/kovalevskaya_diagram.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>

#include "experiments/analysis/accessible_region.hpp"
#include "experiments/analysis/kovalevskaya_critical.hpp"
#include "experiments/analysis/kovalevskaya_regions.hpp"
#include "experiments/analysis/poincare_section.hpp"
#include "experiments/io/number_format.hpp"

namespace lgi::experiments {

namespace {

/// The real roots s ≠ 0 of 2s³ − 2hs² + G = 0 (h = s + G/(2s²)): f is monotone
/// between its critical points 0 and 2h/3, so each sign change is bisected.
std::vector<double> family2_parameters(double h, double G) {
  auto f = [&](double s) { return 2.0 * s * s * s - 2.0 * h * s * s + G; };
  const double bound = 2.0 + 2.0 * std::max(std::abs(h), std::abs(G));
  const std::array<double, 4> ends = {-bound, std::min(0.0, 2.0 * h / 3.0), std::max(0.0, 2.0 * h / 3.0), bound};
  std::vector<double> roots;
  for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
    double a = ends[k], b = ends[k + 1];
    double fa = f(a);
    const double fb = f(b);
    if (a == b || (fa < 0.0) == (fb < 0.0) || fa == 0.0) continue;
    for (int it = 0; it < 200; ++it) {
      const double m = 0.5 * (a + b);
      if (m <= a || m >= b) break;
      const double fm = f(m);
      if ((fm < 0.0) == (fa < 0.0)) a = m, fa = fm;
      else b = m;
    }
    const double s = std::abs(fa) <= std::abs(fb) ? a : b;
    if (s != 0.0) roots.push_back(s);
  }
  return roots;
}

double family2_k(double s, double G) { return 1.0 - G / s + G * G / (4.0 * s * s * s * s); }

/// A chart of the energy surface (ℓ, h) around a direction γ0: γ = unit(γ0 + a t1 + b t2)
/// and the angle α on the ellipse of the remaining kinetic energy (the level-set
/// parametrisation of experiments/SWEEPS.md, "Level set", with a basis that moves smoothly).
struct SurfaceChart {
  const HeavyTopBody* body;
  Mat3 J_inv;
  double l, h;
  Vec3 g0, t1, t2;
  bool state(const Vec3& x, Vec3& gamma, Vec3& Pi) const {
    gamma = (g0 + x(0) * t1 + x(1) * t2).normalized();
    const Vec3 Jg = body->J * gamma;
    const double q = gamma.dot(Jg);
    const double excess = h - body->weight.dot(gamma) - l * l / (2.0 * q);
    if (!(excess >= 0.0)) return false;
    const Vec3 ea = (t1 - t1.dot(gamma) * gamma).normalized(), eb = gamma.cross(ea);
    Eigen::Matrix2d A;
    A << ea.dot(J_inv * ea), ea.dot(J_inv * eb), eb.dot(J_inv * ea), eb.dot(J_inv * eb);
    const Eigen::Matrix2d L = A.llt().matrixL();
    const Eigen::Vector2d y = std::sqrt(2.0 * excess) * L.transpose().triangularView<Eigen::Upper>().solve(
                                                            Eigen::Vector2d(std::cos(x(2)), std::sin(x(2))));
    Pi = (l / q) * Jg + y.x() * ea + y.y() * eb;
    return true;
  }
};

SurfaceChart chart_at(const HeavyTopBody& body, double l, double h, const Vec3& g0) {
  SurfaceChart c{&body, body.J.inverse(), l, h, g0, g0.unitOrthogonal(), Vec3::Zero()};
  c.t2 = g0.cross(c.t1);
  return c;
}

/// Nelder–Mead's simplex method (J. A. Nelder and R. Mead, Comput. J. 7 (1965)
/// 308; the coefficients 1, 2, ½, ½) on f: ℝ³ → ℝ ∪ {+∞}, from x0 with steps `step`.
Vec3 nelder_mead(const std::function<double(const Vec3&)>& f, const Vec3& x0, const Vec3& step, int iterations) {
  std::array<Vec3, 4> x;
  std::array<double, 4> fx;
  x[0] = x0;
  for (int k = 0; k < 3; ++k) x[static_cast<std::size_t>(k + 1)] = x0 + step(k) * Vec3::Unit(k);
  for (std::size_t k = 0; k < 4; ++k) fx[k] = f(x[k]);
  for (int it = 0; it < iterations; ++it) {
    std::array<std::size_t, 4> o = {0, 1, 2, 3};
    std::sort(o.begin(), o.end(), [&](std::size_t a, std::size_t b) { return fx[a] < fx[b]; });
    const std::size_t best = o[0], worst = o[3], second = o[2];
    double size = 0.0;
    for (std::size_t k = 1; k < 4; ++k) size = std::max(size, (x[o[k]] - x[best]).cwiseAbs().maxCoeff());
    if (size < 1e-14 || (std::isfinite(fx[worst]) && fx[worst] - fx[best] <= 1e-16 * std::abs(fx[best]) && size < 1e-9))
      break;
    const Vec3 centre = (x[o[0]] + x[o[1]] + x[o[2]]) / 3.0;
    const Vec3 r = centre + (centre - x[worst]);
    const double fr = f(r);
    if (fr < fx[best]) {
      const Vec3 e = centre + 2.0 * (centre - x[worst]);
      const double fe = f(e);
      if (fe < fr) x[worst] = e, fx[worst] = fe;
      else x[worst] = r, fx[worst] = fr;
    } else if (fr < fx[second]) {
      x[worst] = r, fx[worst] = fr;
    } else {
      const Vec3 c = fr < fx[worst] ? centre + 0.5 * (r - centre) : centre + 0.5 * (x[worst] - centre);
      const double fc = f(c);
      if (fc < std::min(fr, fx[worst])) {
        x[worst] = c, fx[worst] = fc;
      } else {
        for (std::size_t k = 1; k < 4; ++k) {
          x[o[k]] = x[best] + 0.5 * (x[o[k]] - x[best]);
          fx[o[k]] = f(x[o[k]]);
        }
      }
    }
  }
  return x[static_cast<std::size_t>(std::min_element(fx.begin(), fx.end()) - fx.begin())];
}

/// The extreme of sign·k (sign = +1: the least k, −1: the greatest) from a start, polished.
double polish_extreme(const HeavyTopBody& body, const KovalevskayaScale& scale, double l, double h, const Vec3& g0,
                      double alpha0, double sign, double spacing) {
  double best = INFINITY;
  Vec3 start(0.0, 0.0, alpha0), centre = g0;
  for (int round = 0; round < 4; ++round) {
    const SurfaceChart chart = chart_at(body, l, h, centre);
    auto f = [&](const Vec3& x) {
      Vec3 g, Pi;
      return chart.state(x, g, Pi) ? sign * kovalevskaya_k(body, scale, g, Pi) : INFINITY;
    };
    const double size = spacing * std::pow(0.1, round);
    const Vec3 x = nelder_mead(f, start, Vec3(size, size, 0.3 * std::pow(0.3, round)), 4000);
    best = std::min(best, f(x));
    Vec3 g, Pi;
    if (!chart.state(x, g, Pi)) break;
    centre = g, start = Vec3(0.0, 0.0, x(2));  // recentre the chart on the best point
  }
  return sign * best;
}

}  // namespace

double KovalevskayaScale::h(double H) const { return H / (J3 * c); }
double KovalevskayaScale::l(double ell) const { return ell / (J3 * std::sqrt(c)); }

std::optional<KovalevskayaScale> kovalevskaya_scale(const HeavyTopBody& body) {
  const Mat3& J = body.J;
  const bool diagonal = J(0, 1) == 0.0 && J(0, 2) == 0.0 && J(1, 2) == 0.0 && J(1, 0) == 0.0 && J(2, 0) == 0.0 &&
                        J(2, 1) == 0.0;
  const double J3 = J(2, 2);
  if (!diagonal || !(J3 > 0.0) || std::abs(J(0, 0) - J(1, 1)) > 1e-12 * J(0, 0) ||
      std::abs(J(0, 0) - 2.0 * J3) > 1e-12 * J(0, 0) || body.weight.y() != 0.0 || body.weight.z() != 0.0 ||
      body.weight.x() == 0.0)
    return std::nullopt;
  // c < 0 is the same top turned by π about e3 (Γ1, Γ2, Ω1, Ω2 change sign): H, ℓ and K keep their values.
  return KovalevskayaScale{J3, std::abs(body.weight.x()) / J3};
}

double kovalevskaya_k(const HeavyTopBody& body, const KovalevskayaScale& scale, const Vec3& gamma, const Vec3& Pi) {
  const Vec3 W = body.J.inverse() * Pi;
  const double c = body.weight.x() / scale.J3;  // signed, as in the invariant (integrators/system/invariants.cpp)
  const double a = W.x() * W.x() - W.y() * W.y() - c * gamma.x();
  const double b = 2.0 * W.x() * W.y() - c * gamma.y();
  return (a * a + b * b) / (scale.c * scale.c);
}

std::vector<AppelrotPoint> appelrot_curves(double l_scaled, double h_lo, double h_hi, int samples) {
  const double G = 0.5 * l_scaled * l_scaled;
  std::vector<AppelrotPoint> out;
  for (int k = 0; k < samples; ++k) {
    const double h = h_lo + (h_hi - h_lo) * k / std::max(1, samples - 1);
    out.push_back({0, 0, h, h, 0.0});
    out.push_back({1, 0, h, h, (h - G) * (h - G)});
  }
  if (G == 0.0) {  // family 2 is the line k = 1; its s → 0 limit is family 3
    for (int k = 0; k < samples; ++k) {
      const double h = h_lo + (h_hi - h_lo) * k / std::max(1, samples - 1);
      out.push_back({2, h < 0.0 ? -1 : 1, h, h, 1.0});
      if (h > 0.0) out.push_back({3, 0, h, h, 1.0 + h * h});
    }
    return out;
  }
  // Family 2 by its parameter, |s| log-spaced from 1e-4 to 10 (1 + max |h|), each sign.
  const double top = std::log10(10.0 * (1.0 + std::max(std::abs(h_lo), std::abs(h_hi))));
  const int n = 8 * samples;
  for (int sign : {-1, 1})
    for (int k = 0; k < n; ++k) {
      const double s = sign * std::pow(10.0, -4.0 + (top + 4.0) * k / (n - 1));
      const double h = s + G / (2.0 * s * s);
      if (h >= h_lo && h <= h_hi) out.push_back({2, sign, s, h, family2_k(s, G)});
    }
  return out;
}

AppelrotDistance appelrot_distance(double l_scaled, double h, double k) {
  const double G = 0.5 * l_scaled * l_scaled;
  AppelrotDistance d;
  auto consider = [&](int family, double value, double s) {
    if (std::abs(k - value) < d.distance) d.distance = std::abs(k - value), d.family = family, d.s = s;
  };
  consider(0, 0.0, h);
  consider(1, (h - G) * (h - G), h);
  if (G == 0.0) {
    consider(2, 1.0, h);
    if (h > 0.0) consider(3, 1.0 + h * h, h);
  } else {
    for (const double s : family2_parameters(h, G)) consider(2, family2_k(s, G), s);
  }
  return d;
}

std::vector<KRange> kovalevskaya_k_range(const HeavyTopBody& body, const KovalevskayaScale& scale, double l, double h,
                                         int grid) {
  const SphereGrid sphere = potential_grid(body, l, grid);
  const Region region = accessible_region(sphere, critical_points(body, l), h);
  constexpr int angles = 12;
  std::vector<KRange> out;
  for (const auto& component : region.components) {
    double lo = INFINITY, hi = -INFINITY;
    Vec3 g_lo = Vec3::UnitZ(), g_hi = Vec3::UnitZ();
    double a_lo = 0.0, a_hi = 0.0;
    for (int i = 0; i <= grid; ++i)
      for (int j = 0; j < sphere.meridians(); ++j) {
        if (region.label[static_cast<std::size_t>(i * sphere.meridians() + j)] != component.id) continue;
        const Vec3 g0 = sphere.direction(i, j);
        const SurfaceChart chart = chart_at(body, l, h, g0);
        for (int a = 0; a < angles; ++a) {
          const double alpha = 2.0 * std::numbers::pi * a / angles;
          Vec3 g, Pi;
          if (!chart.state(Vec3(0.0, 0.0, alpha), g, Pi)) continue;
          const double k = kovalevskaya_k(body, scale, g, Pi);
          if (k < lo) lo = k, g_lo = g0, a_lo = alpha;
          if (k > hi) hi = k, g_hi = g0, a_hi = alpha;
        }
      }
    if (!std::isfinite(lo)) continue;  // a component without a grid vertex strictly inside
    const double spacing = std::numbers::pi / grid;
    KRange r;
    r.component = component.id;
    r.k_min = std::min(lo, polish_extreme(body, scale, l, h, g_lo, a_lo, 1.0, spacing));
    r.k_max = std::max(hi, polish_extreme(body, scale, l, h, g_hi, a_hi, -1.0, spacing));
    out.push_back(r);
  }
  return out;
}

namespace {

/// The attributes of the five /appelrot* groups: the scaling and what the derived columns mean.
std::vector<TableGroup> described_groups(std::vector<TableGroup> groups, const KovalevskayaScale& scale) {
  const std::string scaling = "h_scaled = H/(J3 c), l_scaled = l/(J3 sqrt(c)), k = K/c^2 (docs/atlas.md section 9)";
  groups[4].attributes["tori_definition"] =
      "the number of connected components of the level set {H = h, K = k, C = l, |Gamma| = 1} (Liouville tori), counted "
      "from lattice states moved onto it; -1 where the linking radii r and 2r disagree "
      "(experiments/analysis/level_set_components.hpp)";
  groups[0].attributes["realised_definition"] =
      "1 where the critical values of (H, K) on the leaf found at the grid energies h_scaled bracketing the point lie on "
      "its family and arc (experiments/analysis/kovalevskaya_critical.hpp; docs/atlas.md section 9)";
  for (TableGroup& g : groups) {
    g.attributes["scaling"] = scaling;
    g.attributes["J3"] = format_general(scale.J3, 17);
    g.attributes["c"] = format_general(scale.c, 17);
  }
  return groups;
}

}  // namespace

std::vector<TableGroup> appelrot_groups(const HeavyTopBody& body, const KovalevskayaScale& scale,
                                        const std::vector<double>& ls, const std::vector<double>& hs,
                                        const std::function<bool(std::size_t)>& l_done) {
  TableGroup curves{"appelrot"}, equilibria{"appelrot_equilibria"}, range{"appelrot_range"},
      criticals{"appelrot_critical"}, regions{"appelrot_regions"};
  std::vector<TableColumn> c = {{"l"}, {"l_scaled"}, {"family", 1, true}, {"branch", 1, true},
                                {"s"}, {"h_scaled"}, {"k"},         {"realised", 1, true}};
  std::vector<TableColumn> e = {{"l"},     {"l_scaled"},     {"h"},     {"h_scaled"},  {"k"},
                                {"omega"}, {"gamma", 3},     {"angular_momentum", 3}, {"family", 1, true},
                                {"distance"}, {"stability", 1, true}};
  std::vector<TableColumn> r = {{"l"}, {"l_scaled"}, {"h"}, {"h_scaled"}, {"component", 1, true}, {"k_min"}, {"k_max"}};
  std::vector<TableColumn> v = {{"l"},        {"l_scaled"},         {"h_scaled"},     {"k"},
                                {"family", 1, true}, {"piece", 1, true}, {"distance"}, {"rank_gap"},
                                {"gamma", 3}, {"angular_momentum_scaled", 3}};
  std::vector<TableColumn> t = {{"l"}, {"l_scaled"}, {"h_scaled"}, {"k"}, {"tori", 1, true}, {"points", 1, true}};
  const HeavyTopBody scaled = scaled_kovalevskaya(body);
  std::vector<double> hs_scaled;
  for (const double h : hs) hs_scaled.push_back(scale.h(h));
  // The poll inside one l (issue 50, item 1: one l takes seconds, more with many energies):
  // l_done with the count so far, before each energy and each level set.
  bool stopped = false;
  std::size_t done = 0;
  const std::function<bool()> keep_going = [&] {
    stopped = stopped || (l_done && !l_done(done));
    return !stopped;
  };
  for (const double l : ls) {
    const double l_scaled = scale.l(l);
    const auto critical = kovalevskaya_critical_values(scaled, l_scaled, hs_scaled, 48, keep_going);
    if (stopped) break;
    const auto curve = appelrot_curves(l_scaled, hs_scaled.front(), hs_scaled.back(), 400);
    const std::vector<int> realised = appelrot_realised(curve, l_scaled, hs_scaled, critical);
    for (std::size_t i = 0; i < curve.size(); ++i) {
      const AppelrotPoint& p = curve[i];
      c[0].real.push_back(l), c[1].real.push_back(l_scaled), c[2].whole.push_back(p.family), c[3].whole.push_back(p.branch);
      c[4].real.push_back(p.s), c[5].real.push_back(p.h), c[6].real.push_back(p.k), c[7].whole.push_back(realised[i]);
    }
    for (const auto& at_h : critical)
      for (const CriticalValue& q : at_h) {
        v[0].real.push_back(l), v[1].real.push_back(l_scaled), v[2].real.push_back(q.h), v[3].real.push_back(q.k);
        v[4].whole.push_back(q.family), v[5].whole.push_back(q.piece), v[6].real.push_back(q.distance);
        v[7].real.push_back(q.rank_gap);
        v[8].real.insert(v[8].real.end(), q.gamma.data(), q.gamma.data() + 3);
        v[9].real.insert(v[9].real.end(), q.Pi.data(), q.Pi.data() + 3);
      }
    for (const auto& q : equilibria_at(body, l).rows) {
      const double k = kovalevskaya_k(body, scale, q.gamma, q.angular_momentum);
      const AppelrotDistance d = appelrot_distance(l_scaled, scale.h(q.h), k);
      e[0].real.push_back(l), e[1].real.push_back(l_scaled), e[2].real.push_back(q.h), e[3].real.push_back(scale.h(q.h));
      e[4].real.push_back(k), e[5].real.push_back(q.omega);
      e[6].real.insert(e[6].real.end(), q.gamma.data(), q.gamma.data() + 3);
      e[7].real.insert(e[7].real.end(), q.angular_momentum.data(), q.angular_momentum.data() + 3);
      e[8].whole.push_back(d.family), e[9].real.push_back(d.distance);
      e[10].whole.push_back(static_cast<std::int64_t>(q.stability));
    }
    const double lowest = minimum_energy(body, l);
    std::vector<RangeAtEnergy> ranges;
    for (const double h : hs) {
      if (!(h > lowest)) continue;
      if (!keep_going()) break;
      ranges.push_back({scale.h(h), kovalevskaya_k_range(body, scale, l, h)});
      for (const auto& k : ranges.back().components) {
        r[0].real.push_back(l), r[1].real.push_back(l_scaled), r[2].real.push_back(h), r[3].real.push_back(scale.h(h));
        r[4].whole.push_back(k.component), r[5].real.push_back(k.k_min), r[6].real.push_back(k.k_max);
      }
    }
    if (stopped) break;
    for (const RegionSample& q : kovalevskaya_region_samples(scaled, l_scaled, ranges, 3, 500, keep_going)) {
      t[0].real.push_back(l), t[1].real.push_back(l_scaled), t[2].real.push_back(q.h), t[3].real.push_back(q.k);
      t[4].whole.push_back(q.tori), t[5].whole.push_back(q.points);
    }
    if (stopped) break;
    done = static_cast<std::size_t>(&l - ls.data()) + 1;
    if (l_done && !l_done(done)) break;
  }
  curves.columns = c, equilibria.columns = e, range.columns = r, criticals.columns = v;
  regions.columns = t;
  return described_groups({curves, equilibria, range, criticals, regions}, scale);
}

}  // namespace lgi::experiments

#include "experiments/analysis/periodic/family_continuation.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>

namespace lgi::experiments {

namespace {

/// The positions of the last two rows without an event (the secant's ends).
std::pair<std::size_t, std::size_t> last_regular_pair(const std::vector<FamilyOrbit>& rows) {
  std::size_t b = rows.size() - 1;
  while (b > 0 && rows[b].event != "none") --b;
  std::size_t a = b == 0 ? 0 : b - 1;
  while (a > 0 && rows[a].event != "none") --a;
  return {a, b};
}

bool in_range(double p, const FamilySettings& s) { return p >= s.h_min && p <= s.h_max; }

FamilyOrbit next_row(const FamilyOrbit& last, const PeriodicOrbit& o) {
  FamilyOrbit r = last;
  r.index = last.index + 1, r.event = "none", r.orbit = o;
  return r;
}

std::string at_h(double h) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.9g", h);
  return buf;
}

/// "h = ..." or "l = ..." (the continued parameter) at p.
std::string at_p(const FamilySettings& s, double p) { return (s.shooting.in_l ? "l = " : "h = ") + at_h(p); }

/// The first step, natural in h: from one orbit (and its equilibrium, if any).
/// Returns "" or why the family ends.
std::string natural_step(const PeriodicFlow& body, std::vector<FamilyOrbit>& rows, double dh, const Vec6* xe,
                         double h_e, const FamilySettings& s) {
  const FamilyOrbit last = rows.back();
  const bool in_l = s.shooting.in_l;
  for (int tries = 0; tries < 5; ++tries, dh *= 0.5) {
    const double p = parameter_of(last.orbit) + dh;
    if (!in_range(p, s)) return in_l ? "l range reached" : "h range reached";
    const double h = in_l ? last.orbit.h : p, l = in_l ? p : last.orbit.l;
    Vec6 x = last.orbit.x0;
    if (xe) x = *xe + std::sqrt((h - h_e) / (last.orbit.h - h_e)) * (last.orbit.x0 - *xe);  // amplitude ∝ √(h − h_e)
    const PeriodicOrbit o = correct_orbit(body, x, last.orbit.period, h, l, s.shooting);
    if (o.converged) {
      rows.push_back(next_row(last, o));
      return "";
    }
  }
  return "the corrector failed at " + at_p(s, parameter_of(last.orbit) + 2.0 * dh) + " after 5 halvings of the first step";
}

/// One pseudo-arclength step of length ds (halved up to five times). Returns "" or why the family ends.
std::string arclength_step(const PeriodicFlow& body, std::vector<FamilyOrbit>& rows, double& ds, double ds0,
                           const FamilySettings& s) {
  const auto [a, b] = last_regular_pair(rows);
  const FamilyPoint za = family_point(rows[a].orbit), zb = family_point(rows[b].orbit);
  const FamilyPoint secant = zb - za;
  const FamilyPoint t = rows[b].orbit.tangent.dot(secant) >= 0.0 ? rows[b].orbit.tangent : -rows[b].orbit.tangent;
  for (int tries = 0; tries < 6; ++tries, ds *= 0.5) {
    const PeriodicOrbit o = correct_on_family(body, zb + ds * t, t, fixed_of(rows[b].orbit), s.shooting);
    if (!o.converged) continue;
    // Against branch jumping: the correction (orthogonal to t) stays below
    // 0.3 Δs, so the new secant turns by less than about 17 degrees.
    if ((family_point(o) - zb - ds * t).norm() > 0.3 * ds) continue;
    if (!in_range(parameter_of(o), s)) return s.shooting.in_l ? "l range reached" : "h range reached";
    rows.push_back(next_row(rows.back(), o));
    ds = std::min(ds0, 2.0 * ds);
    return "";
  }
  return "no step found beyond " + at_p(s, parameter_of(rows[b].orbit)) + " (corrector or branch guard, 6 halvings)";
}

struct Located {
  PeriodicOrbit orbit;
  double s = 0.0;  // the position along the chord
  bool found = false;
};

/// The orbit on the chord z_a → z_b where g(orbit) = 0 (Illinois regula falsi in s),
/// found when |g| ≤ 1e-9 at the best iterate.
template <class G>
Located locate(const PeriodicFlow& body, const PeriodicOrbit& a, const PeriodicOrbit& b, G g, const FamilySettings& s) {
  const FamilyPoint za = family_point(a), chord = family_point(b) - za;
  double s0 = 0.0, s1 = 1.0, g0 = g(a), g1 = g(b);
  int last_side = 0;
  Located best{std::abs(g0) < std::abs(g1) ? a : b, std::abs(g0) < std::abs(g1) ? 0.0 : 1.0, false};
  double best_g = std::min(std::abs(g0), std::abs(g1));
  for (int it = 0; it < 30; ++it) {
    const double sm = (s0 * g1 - s1 * g0) / (g1 - g0);
    const PeriodicOrbit o = correct_on_family(body, za + sm * chord, chord, fixed_of(a), s.shooting);
    if (!o.converged) break;
    const double gm = g(o);
    if (std::abs(gm) < best_g) best = {o, sm, false}, best_g = std::abs(gm);
    if (best_g <= 1e-9 || std::abs(s1 - s0) <= 1e-12) break;
    if ((gm < 0.0) == (g0 < 0.0)) {
      s0 = sm, g0 = gm;
      if (last_side == -1) g1 *= 0.5;
      last_side = -1;
    } else {
      s1 = sm, g1 = gm;
      if (last_side == 1) g0 *= 0.5;
      last_side = 1;
    }
  }
  best.found = best_g <= 1e-9;
  return best;
}

/// Locates the events between the last two regular orbits; a sign change that
/// is not located is added to `notes`.
void locate_events(const PeriodicFlow& body, std::vector<FamilyOrbit>& rows, std::string& notes,
                   const FamilySettings& s) {
  // Not a structured binding: clang 14 (the fuzz preset) cannot capture one in the lambda below.
  const auto pair = last_regular_pair(rows);
  const std::size_t a = pair.first, b = pair.second;
  if (a == b) return;
  const PeriodicOrbit &oa = rows[a].orbit, &ob = rows[b].orbit;
  if (oa.degenerate || ob.degenerate) return;
  std::vector<std::pair<double, FamilyOrbit>> events;
  const auto add = [&](double shift, const char* name) {
    const auto g = [shift](const PeriodicOrbit& o) { return o.reduced_trace - shift; };
    // A dead band: a trace within 1e-8 of ±2 at either end is not a sign.
    if (std::abs(g(oa)) <= 1e-8 || std::abs(g(ob)) <= 1e-8 || (g(oa) < 0.0) == (g(ob) < 0.0)) return;
    const Located found = locate(body, oa, ob, g, s);
    if (!found.found) {
      notes += std::string(notes.empty() ? "" : "; ") + name + " between " + at_p(s, parameter_of(oa)) + " and " +
               at_h(parameter_of(ob)) + " not located";
      return;
    }
    FamilyOrbit r = rows[b];
    r.event = name, r.orbit = found.orbit;
    // A fold: the parameter p (h, or ℓ) turns at the orbit (it lies outside
    // [p_a, p_b], or p's steps before a and after it differ in sign).
    if (shift > 0.0) {
      const double pa = parameter_of(oa), pb = parameter_of(ob), pf = parameter_of(found.orbit);
      bool turns = (pf - pa) * (pb - pf) < 0.0;
      std::size_t p = a;
      while (p > 0 && rows[--p].event != "none") {
      }
      if (p != a && rows[p].event == "none") turns = turns || ((pa - parameter_of(rows[p].orbit) < 0.0) != (pb - pa < 0.0));
      if (turns) r.event = "fold";
    }
    events.emplace_back(found.s, r);
  };
  add(-2.0, "period_doubling");
  add(2.0, "class_change");
  std::sort(events.begin(), events.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<FamilyOrbit> sorted;
  for (auto& e : events) sorted.push_back(std::move(e.second));
  rows.insert(std::next(rows.begin(), static_cast<std::ptrdiff_t>(b)), sorted.begin(), sorted.end());
}

void finish(std::vector<FamilyOrbit>& rows, const std::string& end, const std::string& notes) {
  for (std::size_t k = 0; k < rows.size(); ++k) rows[k].index = static_cast<int>(k);
  if (!rows.empty()) rows.back().family_end = notes.empty() ? end : end + "; " + notes;
}

}  // namespace

void continue_rows(const PeriodicFlow& body, std::vector<FamilyOrbit>& rows, double first_dh, const Vec6* equilibrium,
                   double h_equilibrium, const FamilySettings& s, double ds0) {
  int taken = 0;
  std::string notes, end = "steps done";
  if (rows.size() == 1) {
    if (s.steps == 0) return finish(rows, end, notes);
    if (std::string why = natural_step(body, rows, first_dh, equilibrium, h_equilibrium, s); !why.empty())
      return finish(rows, why, notes);
    ++taken;
    if (s.locate_events) locate_events(body, rows, notes, s);
  }
  if (!(ds0 > 0.0)) {
    const auto [a, b] = last_regular_pair(rows);
    ds0 = (family_point(rows[b].orbit) - family_point(rows[a].orbit)).norm();
  }
  double ds = ds0;
  for (; taken < s.steps; ++taken) {
    if (std::string why = arclength_step(body, rows, ds, ds0, s); !why.empty()) {
      end = why;
      break;
    }
    if (s.locate_events) locate_events(body, rows, notes, s);
  }
  finish(rows, end, notes);
}

std::vector<FamilyOrbit> doubled_family(const PeriodicFlow& body, const FamilyOrbit& pd, int family,
                                        const FamilySettings& s, std::string& why_not) {
  const PeriodicOrbit& o = pd.orbit;
  // The eigenvector of P for −1: at a period doubling A = P + I has rank one
  // and A² = (tr A) A ≈ 0, so its column space is its null space: its larger column.
  const Eigen::Matrix2d A = o.reduced_monodromy + Eigen::Matrix2d::Identity();
  const Eigen::Vector2d v2 = A.col(A.col(0).norm() >= A.col(1).norm() ? 0 : 1);
  if (!(v2.norm() > 0.0)) {
    why_not = "P + I vanishes (a double multiplier −1 with two eigenvectors)";
    return {};
  }
  // The direction off the doubled parent: v, made orthogonal to the parent
  // family's tangent taken twice round, (τ_x, 2τ_T, τ_h), which also solves
  // the doubled equations.
  FamilyPoint parent = o.tangent;
  parent(6) *= 2.0;
  parent.normalize();
  FamilyPoint t = FamilyPoint::Zero();
  t.head<6>() = o.section_basis * v2;
  t = (t - t.dot(parent) * parent).normalized();
  FamilyPoint z_pd;
  z_pd << o.x0, 2.0 * o.period, parameter_of(o);
  std::vector<FamilyOrbit> rows;
  for (const double k : {1.0, 2.0}) {
    const double eps = k * s.switch_amplitude * o.x0.norm();
    const PeriodicOrbit d = correct_on_family(body, z_pd + eps * t, t, fixed_of(o), s.shooting);
    if (!d.converged) {
      why_not = "the corrector failed at amplitude " + at_h(eps);
      return {};
    }
    // Off the doubled parent (not periodic with half its period), and of period ≈ 2T.
    const Shot half = shoot(body, d.x0, 0.5 * d.period, s.shooting.dt);
    if (!half.ok || flow_difference(body, half.end, d.x0).norm() <= 1e-3 * eps || std::abs(d.period - 2.0 * o.period) > 0.1 * o.period) {
      why_not = "the orbit found at amplitude " + at_h(eps) + " is the doubled parent or not of period 2T";
      return {};
    }
    FamilyOrbit r;
    r.family = family, r.index = static_cast<int>(rows.size()), r.parent = pd.family;
    r.omega = 2.0 * std::acos(-1.0) / d.period, r.orbit = d;
    rows.push_back(r);
  }
  continue_rows(body, rows, 0.0, nullptr, 0.0, s, std::max(s.h_step, (family_point(rows[1].orbit) - family_point(rows[0].orbit)).norm()));
  return rows;
}

}  // namespace lgi::experiments

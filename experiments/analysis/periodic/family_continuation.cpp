#include "experiments/analysis/periodic/family_continuation.hpp"

#include <Eigen/LU>
#include <cmath>
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

bool in_range(double h, const FamilySettings& s) { return h >= s.h_min && h <= s.h_max; }

FamilyOrbit next_row(const FamilyOrbit& last, const PeriodicOrbit& o) {
  FamilyOrbit r = last;
  r.index = last.index + 1, r.event = "none", r.orbit = o;
  return r;
}

/// The first step, natural in h: from one orbit (and its equilibrium, if any).
bool natural_step(const HeavyTopBody& body, std::vector<FamilyOrbit>& rows, double dh, const Vec6* xe, double h_e,
                  const FamilySettings& s) {
  const FamilyOrbit last = rows.back();
  for (int tries = 0; tries < 5; ++tries, dh *= 0.5) {
    const double h = last.orbit.h + dh;
    if (!in_range(h, s)) return false;
    Vec6 x = last.orbit.x0;
    if (xe) x = *xe + std::sqrt((h - h_e) / (last.orbit.h - h_e)) * (last.orbit.x0 - *xe);  // amplitude ∝ √(h − h_e)
    const PeriodicOrbit o = correct_orbit(body, x, last.orbit.period, h, last.orbit.l, s.shooting);
    if (o.converged) {
      rows.push_back(next_row(last, o));
      return true;
    }
  }
  return false;
}

/// One pseudo-arclength step of length ds (halved up to four times).
bool arclength_step(const HeavyTopBody& body, std::vector<FamilyOrbit>& rows, double& ds, double ds0,
                    const FamilySettings& s) {
  const auto [a, b] = last_regular_pair(rows);
  const FamilyPoint za = family_point(rows[a].orbit), zb = family_point(rows[b].orbit);
  const FamilyPoint secant = zb - za;
  const FamilyPoint t = rows[b].orbit.tangent.dot(secant) >= 0.0 ? rows[b].orbit.tangent : -rows[b].orbit.tangent;
  for (int tries = 0; tries < 6; ++tries, ds *= 0.5) {
    const PeriodicOrbit o = correct_on_family(body, zb + ds * t, t, rows[b].orbit.l, s.shooting);
    if (!o.converged) continue;
    // Against branch jumping: the correction stays small beside the step, and
    // the new secant turns by less than about 25 degrees.
    const FamilyPoint z = family_point(o);
    if ((z - zb - ds * t).norm() > 0.3 * ds || (z - zb).normalized().dot(t) < 0.9) continue;
    if (!in_range(o.h, s)) return false;
    rows.push_back(next_row(rows.back(), o));
    ds = std::min(ds0, 2.0 * ds);
    return true;
  }
  return false;
}

/// The orbit on the chord z_a → z_b where g(orbit) = 0 (Illinois regula falsi in s).
template <class G>
PeriodicOrbit locate(const HeavyTopBody& body, const PeriodicOrbit& a, const PeriodicOrbit& b, G g,
                     const FamilySettings& s, bool& found) {
  const FamilyPoint za = family_point(a), chord = family_point(b) - za;
  double s0 = 0.0, s1 = 1.0, g0 = g(a), g1 = g(b);
  int last_side = 0;
  PeriodicOrbit best = std::abs(g0) < std::abs(g1) ? a : b;
  found = false;
  for (int it = 0; it < 30; ++it) {
    const double sm = (s0 * g1 - s1 * g0) / (g1 - g0);
    const PeriodicOrbit o = correct_on_family(body, za + sm * chord, chord, a.l, s.shooting);
    if (!o.converged) return best;
    const double gm = g(o);
    best = o;
    if (std::abs(gm) <= 1e-9 || std::abs(s1 - s0) <= 1e-12) break;
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
  found = true;
  return best;
}

/// Locates the events between the last regular orbit before the newest and the newest.
void locate_events(const HeavyTopBody& body, std::vector<FamilyOrbit>& rows, const FamilySettings& s) {
  const auto [a, b] = last_regular_pair(rows);
  if (a == b) return;
  const PeriodicOrbit &oa = rows[a].orbit, &ob = rows[b].orbit;
  std::vector<FamilyOrbit> events;
  const auto add = [&](double shift, const char* name) {
    const auto g = [shift](const PeriodicOrbit& o) { return o.reduced_trace - shift; };
    if (!((g(oa) < 0.0) != (g(ob) < 0.0)) || oa.degenerate || ob.degenerate) return;
    bool found = false;
    const PeriodicOrbit o = locate(body, oa, ob, g, s, found);
    if (!found) return;
    FamilyOrbit r = rows[b];
    r.event = name, r.orbit = o;
    // A fold: h turns at the orbit (it lies outside [h_a, h_b] or h_a − h_pre, h_b − h_a differ in sign).
    if (shift > 0.0 && a > 0) {
      const double before = oa.h - rows[a - 1].orbit.h, after = ob.h - oa.h;
      if ((before < 0.0) != (after < 0.0) || (o.h - oa.h) * (ob.h - o.h) < 0.0) r.event = "fold";
    }
    events.push_back(r);
  };
  add(-2.0, "period_doubling");
  add(2.0, "class_change");
  rows.insert(std::next(rows.begin(), static_cast<std::ptrdiff_t>(b)), events.begin(), events.end());
}

void renumber(std::vector<FamilyOrbit>& rows) {
  for (std::size_t k = 0; k < rows.size(); ++k) rows[k].index = static_cast<int>(k);
}

}  // namespace

void continue_rows(const HeavyTopBody& body, std::vector<FamilyOrbit>& rows, double first_dh, const Vec6* equilibrium,
                   double h_equilibrium, const FamilySettings& s) {
  int taken = 0;
  if (rows.size() == 1) {
    if (s.steps == 0 || !natural_step(body, rows, first_dh, equilibrium, h_equilibrium, s)) return renumber(rows);
    ++taken;
    if (s.locate_events) locate_events(body, rows, s);
  }
  const auto [a, b] = last_regular_pair(rows);
  const double ds0 = (family_point(rows[b].orbit) - family_point(rows[a].orbit)).norm();
  double ds = ds0;
  for (; taken < s.steps; ++taken) {
    if (!arclength_step(body, rows, ds, ds0, s)) break;
    if (s.locate_events) locate_events(body, rows, s);
  }
  renumber(rows);
}

std::vector<FamilyOrbit> doubled_family(const HeavyTopBody& body, const FamilyOrbit& pd, int family,
                                        const FamilySettings& s) {
  const PeriodicOrbit& o = pd.orbit;
  // The eigenvector of P for −1: the null vector of P + I, taken from its larger column's normal.
  const Eigen::Matrix2d A = o.reduced_monodromy + Eigen::Matrix2d::Identity();
  const int c = A.col(0).norm() >= A.col(1).norm() ? 0 : 1;
  const Eigen::Vector2d v2(-A(1, c), A(0, c));
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
  z_pd << o.x0, 2.0 * o.period, o.h;
  std::vector<FamilyOrbit> rows;
  for (const double k : {1.0, 2.0}) {
    const double eps = k * s.switch_amplitude * o.x0.norm();
    const PeriodicOrbit d = correct_on_family(body, z_pd + eps * t, t, o.l, s.shooting);
    // Off the doubled parent: not periodic with half its period.
    if (!d.converged || (shoot(body, d.x0, 0.5 * d.period, s.shooting.dt).end - d.x0).norm() <= 1e-3 * eps) return {};
    FamilyOrbit r;
    r.family = family, r.index = static_cast<int>(rows.size()), r.parent = pd.family;
    r.omega = 2.0 * std::acos(-1.0) / d.period, r.orbit = d;
    rows.push_back(r);
  }
  continue_rows(body, rows, 0.0, nullptr, 0.0, s);
  return rows;
}

}  // namespace lgi::experiments

// The Lagrange closed form (experiments/analysis/actions_closed_form.cpp,
// docs/actions.md §1) on a grid of the energy surface that holds the lines
// ℓ = ±L3 (tori through the hanging and the upright position) and the apex
// ℓ = L3 = 0, against an independent quadrature written directly from the
// Hamiltonian in the nutation angle θ:
//   p_θ² = 2A(h − L3²/(2C) − w cosθ) − (ℓ − L3 cosθ)²/sin²θ,  I_θ = (1/π)∫ p_θ dθ
// over the interval where p_θ² ≥ 0, its ends found by a scan and bisection in θ
// (a pole is an end where the interval reaches it), the integral by Boost's
// tanh-sinh rule (robust at the square-root ends). Nothing of the closed
// form's cubic, its roots or its elliptic integrals is shared.
#include <catch2/catch.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <cmath>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include "experiments/analysis/actions.hpp"

namespace test_actions_lagrange_poles {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using lgi::experiments::LagrangeBody;

namespace {

constexpr double pi = std::numbers::pi;

struct Direct {
  double I = 0.0;  // (1/π)∫ p_θ dθ
  double width = 0.0;  // θ2 − θ1
};

/// p_θ² at θ, its removable singularity at a pole (ℓ = ±L3) taken by continuity: the
/// centrifugal term written with sin²θ = (1 − c)(1 + c), c = cosθ.
double p_theta_squared(const LagrangeBody& b, double l, double L3, double h, double theta) {
  const double c = std::cos(theta);
  const double q = (l - L3 * c) * (l - L3 * c);
  const double s2 = std::sin(theta) * std::sin(theta);
  return 2.0 * b.A * (h - L3 * L3 / (2.0 * b.C) - b.w * c) - q / s2;
}

/// The end of the interval between θ_in (p² > 0) and θ_out (p² ≤ 0), by bisection.
double bisect_end(const LagrangeBody& b, double l, double L3, double h, double in, double out) {
  for (int i = 0; i < 200; ++i) {
    const double m = 0.5 * (in + out);
    if (m == in || m == out) break;
    (p_theta_squared(b, l, L3, h, m) > 0.0 ? in : out) = m;
  }
  return 0.5 * (in + out);
}

/// The quadrature, or nothing if p_θ² > 0 nowhere (or on more than one interval).
std::optional<Direct> direct_action(const LagrangeBody& b, double l, double L3, double h) {
  constexpr int scan = 4000;
  std::vector<double> theta(scan + 1);
  for (int i = 0; i <= scan; ++i) theta[static_cast<std::size_t>(i)] = pi * i / scan;
  int first = -1, last = -1, pieces = 0;
  bool inside = false;
  for (int i = 1; i < scan; ++i) {
    const bool pos = p_theta_squared(b, l, L3, h, theta[static_cast<std::size_t>(i)]) > 0.0;
    if (pos && !inside) ++pieces, first = first < 0 ? i : first;
    if (pos) last = i;
    inside = pos;
  }
  if (pieces != 1) return std::nullopt;
  const auto at = [&](int i) { return theta[static_cast<std::size_t>(i)]; };
  // An interval reaching the scan's first or last interior node ends at the pole when p_θ² stays
  // positive up to it (ℓ = ∓L3), else at a turning point between.
  auto end_at = [&](int i, int j, double pole) {
    if ((i == 1 || i == scan - 1) && p_theta_squared(b, l, L3, h, pole == 0.0 ? 1e-9 : pi - 1e-9) > 0.0) return pole;
    return bisect_end(b, l, L3, h, at(i), at(j));
  };
  const double t1 = end_at(first, first - 1, 0.0), t2 = end_at(last, last + 1, pi);
  boost::math::quadrature::tanh_sinh<double> rule;
  const auto p = [&](double t) { return std::sqrt(std::max(0.0, p_theta_squared(b, l, L3, h, t))); };
  const double I = rule.integrate(p, t1, t2, 1e-14) / pi;
  return Direct{I, t2 - t1};
}

}  // namespace

TEST_CASE("Lagrange closed form on and off l = +-L3 agrees with a direct quadrature in theta", "[actions]") {
  // The cigar of `lgi actions --h 2` (experiments/scenes/lagrange_top_cigar.toml), a disk, and
  // the cigar hung the other way (w < 0: the lines swap roles).
  struct Case {
    LagrangeBody body;
    double h;
  };
  for (const Case& c : {Case{{1.0, 0.5, 1.0}, 2.0}, Case{{0.6, 1.0, 1.0}, 1.5}, Case{{1.0, 0.5, -1.0}, 2.0},
                        Case{{1.0, 0.5, 1.0}, 0.5}}) {
    const LagrangeBody& b = c.body;
    const auto surface = lgi::experiments::lagrange_surface(b, c.h, 21);
    const double L = std::sqrt(2.0 * std::max(b.A, b.C) * (c.h + std::abs(b.w)));
    int on_lines = 0, compared = 0;
    bool apex = false;
    for (int i = 0; i < 21; ++i)
      for (int j = 0; j < 21; ++j) {
        const double l = L * (2 * i - 20) / 20, L3 = L * (2 * j - 20) / 20;
        const auto d = direct_action(b, l, L3, c.h);
        const auto a = lgi::experiments::lagrange_actions(b, l, L3, c.h);
        INFO("A=" << b.A << " C=" << b.C << " w=" << b.w << " h=" << c.h << " l=" << l << " L3=" << L3);
        // Every node with a torus of positive width has the closed form, and no other node.
        if (d && d->width > 1e-3) REQUIRE(a);
        if (!d) CHECK(!a);
        if (!a || !d) continue;
        ++compared;
        if (std::abs(l) == std::abs(L3)) ++on_lines;
        if (l == 0.0 && L3 == 0.0) apex = true;
        INFO("closed " << a->actions[2] << " direct " << d->I);
        CHECK(std::abs(a->actions[2] - d->I) < 1e-8 * d->I);
        // lagrange_surface holds the same torus (the grid of 21 nodes per axis).
        bool listed = false;
        for (const auto& s : surface)
          if (s.actions[0] == l && s.actions[1] == L3) listed = s.actions[2] == a->actions[2];
        CHECK(listed);
      }
    INFO("h=" << c.h << " w=" << b.w);
    CHECK(compared > 100);
    CHECK(on_lines > 8);
    if (c.h > std::abs(b.w)) CHECK(apex);  // above the upright position the planar pendulum circulates
  }
}

TEST_CASE("Lagrange actions are continuous across l = +-L3 and the grid holds the apex", "[actions]") {
  const LagrangeBody b{1.0, 0.5, 1.0};
  // The points of the trial (experiments/scenes/lagrange_top_cigar.toml, `--h 2`, nodes of the
  // 61-node grid): on the line the old closed form gave 0.3914 and 0.5807, the quadrature
  // 0.6378 and 1.2018; here both signs of the line and a point near the apex.
  const double L = std::sqrt(6.0);
  for (const auto& [node, expected] : {std::pair{45, 0.6378}, std::pair{39, 1.2018}, std::pair{33, 0.0}}) {
    const double L3 = L * (2 * node - 60) / 60;
    for (const double s : {1.0, -1.0}) {
      const double l = -s * L3;
      INFO("l=" << l << " L3=" << s * L3);
      const auto on = lgi::experiments::lagrange_actions(b, l, s * L3, 2.0);
      REQUIRE(on);
      const auto d = direct_action(b, l, s * L3, 2.0);
      REQUIRE(d);
      CHECK(std::abs(on->actions[2] - d->I) < 1e-8 * d->I);
      // On ℓ = −L3 (w > 0) the torus passes through the hanging position: u1 = −1 exactly.
      if (s > 0) CHECK(on->u1 == -1.0);
      if (s > 0 && expected > 0.0) CHECK(std::abs(on->actions[2] - expected) < 1e-4);
      for (const double e : {1e-6, -1e-6, 1e-10, -1e-10}) {
        const auto off = lgi::experiments::lagrange_actions(b, l + e, s * L3, 2.0);
        REQUIRE(off);
        CHECK(std::abs(off->actions[2] - on->actions[2]) < 10 * std::abs(e));  // a crease: O(|ℓ ± L3|)
      }
    }
  }
  // The apex: the planar pendulum over the top, I = (1/π)∫_0^π √(2A(h − w cosθ)) dθ.
  const auto apex = lgi::experiments::lagrange_actions(b, 0.0, 0.0, 2.0);
  REQUIRE(apex);
  boost::math::quadrature::tanh_sinh<double> rule;
  const double I = rule.integrate([](double t) { return std::sqrt(2.0 * (2.0 - std::cos(t))); }, 0.0, pi, 1e-14) / pi;
  CHECK(std::abs(apex->actions[2] - I) < 1e-12);
  // Even --grid values are raised to odd ones: the apex is a node.
  for (const int n : {2, 10, 61}) {
    bool found = false;
    for (const auto& a : lgi::experiments::lagrange_surface(b, 2.0, n))
      found = found || (a.actions[0] == 0.0 && a.actions[1] == 0.0);
    CHECK(found);
  }
}

TEST_CASE("Lagrange actions on a separatrix (u2 = u3) are refused, not an elliptic-integral error", "[actions]") {
  // ℓ = L3 = 0 at h = w: the planar pendulum's homoclinic orbit to the upright position, where
  // f(u) = (2w/A)(1 − u)²(1 + u) has the double root u2 = u3 = 1 (`lgi actions --h 1` on
  // experiments/scenes/lagrange_top_oblate.toml stopped with a Boost domain error there).
  for (const LagrangeBody& b : {LagrangeBody{0.9, 1.0, 1.0}, LagrangeBody{1.0, 0.5, 1.0}, LagrangeBody{0.6, 1.0, 2.0}}) {
    INFO("A=" << b.A << " C=" << b.C << " w=" << b.w);
    CHECK(!lgi::experiments::lagrange_actions(b, 0.0, 0.0, b.w));
    const auto surface = lgi::experiments::lagrange_surface(b, b.w, 61);
    CHECK(surface.size() > 100);
    for (const auto& a : surface) CHECK(std::isfinite(a.actions[2]));
  }
}

}  // namespace test_actions_lagrange_poles

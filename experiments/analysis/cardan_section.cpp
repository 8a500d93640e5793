#include "experiments/analysis/cardan_section.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "experiments/analysis/cardan_equilibria.hpp"
#include "experiments/analysis/seeded_random.hpp"
#include "experiments/errors/exit_status.hpp"
#include "integrators/loop_support.hpp"
#include "integrators/torus/torus_explicit.hpp"
#include "integrators/torus/torus_implicit.hpp"
#include "integrators/ensemble/cardan_tangent_ensemble.hpp"

namespace lgi::experiments {
namespace {

using integrators::StepStatus;
using integrators::WorkCounters;
using system::TorusState;
constexpr double pi = std::numbers::pi;
constexpr std::uint64_t draw_stream = 0x5ec7104ULL, tangent_stream = 0x7a1e5cULL;

/// The two factors of S = −sin q2 · q̇2 (header): 0 is q̇2, 1 is sin q2.
double factor(const system::CardanTop& top, const TorusState& x, int which) {
  return which == 0 ? top.velocity(x)(1) : std::sin(x.q(1));
}
double section_value(const system::CardanTop& top, const TorusState& x) {
  return -std::sin(x.q(1)) * top.velocity(x)(1);
}

CardanCrossing crossing_at(const system::CardanTop& top, const TorusState& x, double t, int which, int direction) {
  CardanCrossing c;
  c.t = t, c.x = x, c.direction = direction;
  const Vec3 v = top.velocity(x);
  c.x_coord = wrap_angle_positive(x.q(2));
  if (which == 0) {
    c.piece = v(2) >= 0.0 ? 1 : -1;
    c.y_coord = wrap_angle_positive(x.q(1));
  } else {
    c.piece = std::cos(x.q(1)) > 0.0 ? 2 : 3;
    c.y_coord = std::atan2(v(2), v(1));
  }
  return c;
}

/// θ in (0, 1] where factor `which` of the step map from `before` vanishes
/// (Illinois regula falsi; M. Dowell, P. Jarratt, BIT 11 (1971) 168), and the state there.
template <class Scheme>
double locate(const Scheme& scheme, const system::CardanTop& top, const TorusState& before, double t, double h,
              int which, TorusState& at) {
  WorkCounters scratch;
  auto value = [&](double theta, TorusState& x) {
    x = before;
    Scheme copy = scheme;
    copy.step(top, x, t, theta * h, scratch);
    return factor(top, x, which);
  };
  double lo = 0.0, hi = 1.0, f_lo = factor(top, before, which), f_hi = value(1.0, at);
  int side = 0;
  for (int it = 0; it < 100 && hi - lo > 4e-16; ++it) {
    const double theta = f_hi != f_lo ? std::clamp(hi - f_hi * (hi - lo) / (f_hi - f_lo), lo, hi) : 0.5 * (lo + hi);
    TorusState x;
    const double f = value(theta, x);
    if (f == 0.0) return at = x, theta;
    if ((f > 0.0) == (f_hi > 0.0)) {
      hi = theta, f_hi = f;
      if (side == 1) f_lo *= 0.5;
      side = 1;
    } else {
      lo = theta, f_lo = f;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    }
  }
  value(hi, at);
  return hi;
}

bool changes_sign(double a, double b) { return (a < 0.0 && b >= 0.0) || (a > 0.0 && b <= 0.0); }

template <class Scheme>
void integrate_orbit(const system::CardanTop& top, const CardanOrbitRequest& r, CardanOrbit& o) {
  Scheme scheme;
  WorkCounters work;
  TorusState x = o.initial;
  // Errors relative to max(|H0|, T0), T0 the kinetic energy: H0 may be 0 on a level set.
  const double H0 = top.energy(x), p10 = x.p(0);
  const double energy_scale = std::max({std::abs(H0), 0.5 * x.p.dot(top.velocity(x)), 1e-300});
  if (std::string why = integrators::fixed_step_grid_problem(0.0, r.t_end, r.dt); !why.empty()) {
    o.status = 1;  // never a finished orbit with no steps
    o.reason = std::move(why);
    return;
  }
  const std::int64_t n = integrators::fixed_step_count(r.t_end, r.dt);
  double t = 0.0;
  for (std::int64_t k = 0; k < n; ++k) {
    const double t_next = k + 1 == n ? r.t_end : static_cast<double>(k + 1) * r.dt;
    const TorusState before = x;
    const StepStatus st = scheme.step(top, x, t, t_next - t, work);
    o.steps = k + 1;
    if (!st.converged || !(x.q.allFinite() && x.p.allFinite())) {
      o.status = 1;
      o.reason = (st.converged ? "state became non-finite at t = " : "implicit solve did not converge at t = ") +
                 std::to_string(t_next);
      x = before;
      break;
    }
    o.max_energy_error = std::max(o.max_energy_error, std::abs(top.energy(x) - H0) / energy_scale);
    o.max_momentum_error = std::max(o.max_momentum_error, std::abs(x.p(0) - p10) / std::max(std::abs(p10), 1e-300));
    const int direction = section_value(top, x) > section_value(top, before) ? 1 : -1;
    std::vector<CardanCrossing> found;
    for (int which = 0; which < 2; ++which)
      if (changes_sign(factor(top, before, which), factor(top, x, which))) {
        TorusState at;
        const double theta = locate(scheme, top, before, t, t_next - t, which, at);
        found.push_back(crossing_at(top, at, t + theta * (t_next - t), which, direction));
      }
    std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.t < b.t; });
    for (const auto& c : found) {
      if (static_cast<std::int64_t>(o.crossings.size()) >= r.max_crossings) {
        o.status = 3;
        o.reason = "more than " + std::to_string(r.max_crossings) + " crossings (--max-events)";
        break;
      }
      o.crossings.push_back(c);
    }
    t = t_next;
    if (o.status == 3) break;
  }
  o.final = x;
}

}  // namespace

void check_cardan_section_scheme(const std::string& name) {
  if (name != "cardan-rk4" && name != "cardan-midpoint" && name != "cardan-dg")
    throw UsageError("--scheme: " + name + ": lgi poincare on a Cardan top takes a fixed-step T^3 scheme: "
                     "cardan-rk4, cardan-midpoint or cardan-dg");
}

bool draw_cardan_level_point(const system::CardanTop& top, double l, double h, std::uint64_t seed,
                             std::int64_t index, TorusState& x) {
  CounterRng rng(seed, index, draw_stream);
  for (int attempt = 0; attempt < 100000; ++attempt) {
    const double q2 = -pi + 2.0 * pi * rng.uniform(), q3 = 2.0 * pi * rng.uniform(), phi = 2.0 * pi * rng.uniform();
    const double surplus = h - cardan_amended_potential(top, l, q2, q3);
    if (!(surplus >= 0.0)) continue;
    const Vec3 q(0.0, q2, q3);
    const Mat3 M = top.mass_matrix(q);
    const Eigen::Matrix2d S = M.block<2, 2>(1, 1) - M.block<2, 1>(1, 0) * M.block<1, 2>(0, 1) / M(0, 0);
    const Eigen::LLT<Eigen::Matrix2d> llt(S);
    if (llt.info() != Eigen::Success) continue;  // M singular here (gimbal lock without ring inertia)
    const Eigen::Vector2d u =
        std::sqrt(2.0 * surplus) * llt.matrixU().solve(Eigen::Vector2d(std::cos(phi), std::sin(phi)));
    const Vec3 qdot((l - M(0, 1) * u(0) - M(0, 2) * u(1)) / M(0, 0), u(0), u(1));
    x = top.from_rates(q, qdot);
    x.p(0) = l;  // = M₁· q̇ up to round-off; the level's value exactly
    return true;
  }
  return false;
}

namespace {

/// The orbit's first tangent vector: a draw of the unit cube from (seed, index).
system::Vec6 orbit_tangent(std::uint64_t seed, std::int64_t index) {
  CounterRng rng(seed, index, tangent_stream);
  system::Vec6 v;
  for (int k = 0; k < 6; ++k) v(k) = 2.0 * rng.uniform() - 1.0;
  return v;
}

}  // namespace

void cardan_orbit_indicators(const system::CardanTop& top, const TorusState& x0, double t_end, double dt,
                             std::uint64_t seed, std::int64_t index, double& lyapunov, double& megno,
                             const std::atomic<bool>* stop) {
  system::Vec6 x = system::stack(x0);
  const auto ind = integrators::ensemble::scalar_cardan_chaos_indicators(integrators::ensemble::cardan_lane_model(top),
                                                                         x, orbit_tangent(seed, index), t_end, dt, stop);
  lyapunov = ind.lyapunov, megno = ind.megno;
}

void cardan_orbit_indicators(const system::CardanTop& top, std::span<const TorusState> x0, double t_end, double dt,
                             std::uint64_t seed, std::span<const std::int64_t> index,
                             std::optional<integrators::ensemble::Isa> isa, std::span<double> lyapunov,
                             std::span<double> megno, const std::atomic<bool>* stop) {
  std::optional<integrators::ensemble::CardanTangentEnsemble> e;
  if (isa && x0.size() > 1) e = integrators::ensemble::CardanTangentEnsemble::make(top, *isa);  // one orbit: the scalar step
  if (!e) {
    for (std::size_t k = 0; k < x0.size(); ++k)
      cardan_orbit_indicators(top, x0[k], t_end, dt, seed, index[k], lyapunov[k], megno[k], stop);
    return;
  }
  const auto width = static_cast<std::size_t>(e->lanes());
  for (std::size_t first = 0; first < x0.size(); first += width) {
    const std::size_t n = std::min(width, x0.size() - first);
    for (std::size_t l = 0; l < n; ++l)
      e->set_lane(static_cast<int>(l), system::stack(x0[first + l]), orbit_tangent(seed, index[first + l]));
    integrators::ChaosIndicators r[integrators::ensemble::max_lanes];
    e->chaos_indicators(0.0, t_end, dt, stop, {r, n});
    for (std::size_t l = 0; l < n; ++l) lyapunov[first + l] = r[l].lyapunov, megno[first + l] = r[l].megno;
  }
}

CardanOrbit cardan_orbit(const system::CardanTop& top, const TorusState& x0, const CardanOrbitRequest& r,
                         std::int64_t index) {
  CardanOrbit o;
  o.initial = x0;
  const double cpu0 = integrators::detail::cpu_now();
  if (r.scheme == "cardan-midpoint") integrate_orbit<integrators::torus::TorusMidpoint>(top, r, o);
  else if (r.scheme == "cardan-dg") integrate_orbit<integrators::torus::TorusDiscreteGradient>(top, r, o);
  else integrate_orbit<integrators::torus::TorusRk4>(top, r, o);
  if (r.indicators) cardan_orbit_indicators(top, x0, r.t_end, r.dt, r.seed, index, o.lyapunov, o.megno);
  o.cpu_seconds = integrators::detail::cpu_now() - cpu0;
  return o;
}

}  // namespace lgi::experiments

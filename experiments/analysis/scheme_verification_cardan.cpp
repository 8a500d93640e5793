// The verification kit's checks on T³ × ℝ³ (scheme_verification_cardan.hpp
// states them and their bounds).
#include "experiments/analysis/scheme_verification_cardan.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <limits>
#include <sstream>
#include <vector>

// odeint copies its steppers' scratch arrays before their first use, which
// GCC reports (-Wuninitialized) once inlined; the copies are overwritten
// before they are read.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/numeric/odeint.hpp>
#pragma GCC diagnostic pop

#include "experiments/io/scene_reader.hpp"
#include "experiments/io/scene_suspension.hpp"

namespace lgi::experiments::verification {
namespace {

constexpr double symmetry_bound = 1e-13;
constexpr double symplecticity_bound = 1e-7;
constexpr double conservation_bound = 1e-12;
const char* const order_scenes[] = {"cardan_euler_tilted", "cardan_general_horizontal"};

/// The reference at t_end: rkf78 (Boost.Odeint) on ℝ⁶ at tol 1e-14, only CardanTop::field shared.
system::TorusState reference_state(const system::CardanTop& top, const system::TorusState& x0, double t_end) {
  namespace odeint = boost::numeric::odeint;
  using Vector = std::array<double, 6>;
  Vector x{x0.q[0], x0.q[1], x0.q[2], x0.p[0], x0.p[1], x0.p[2]};
  auto field = [&](const Vector& y, Vector& dy, double) {
    const system::Vec6 f = top.field({lie::Vec3(y[0], y[1], y[2]), lie::Vec3(y[3], y[4], y[5])});
    for (int i = 0; i < 6; ++i) dy[static_cast<std::size_t>(i)] = f[i];
  };
  auto stepper = odeint::make_controlled<odeint::runge_kutta_fehlberg78<Vector>>(1e-14, 1e-14);
  odeint::integrate_adaptive(stepper, field, x, 0.0, t_end, 1e-3);
  return {lie::Vec3(x[0], x[1], x[2]), lie::Vec3(x[3], x[4], x[5])};
}

Check cardan_check(std::string name, const std::string& problem, bool passed, std::string detail) {
  return {std::move(name), problem, passed, std::move(detail), true};
}

void cardan_order_checks(const integrators::SchemeInfo& s, const Options& o, Report& report) {
  if (s.order == 0) return;
  const double t_end = cardan_order_t_end;
  for (const char* name : order_scenes) {
    const CardanProblem p = load_cardan_problem(o.scenes_dir, name);
    const system::TorusState ref = reference_state(p.top, p.scene.cardan_initial, t_end);
    integrators::BasicNullObserver<system::TorusState> none;
    Check c;
    if (s.properties.adaptive) {
      std::vector<ConvergencePoint> all;
      for (double tol = 1e-3; tol >= 1e-13; tol /= std::sqrt(10.0)) {
        system::TorusState x = p.scene.cardan_initial;
        const integrators::RunStats st = run_cardan_span(s, p.top, x, 0.0, t_end, 0.0, tol, none);
        if (!st.ok || st.steps == 0) continue;
        all.push_back({t_end / static_cast<double>(st.steps), cardan_error(x, ref)});
      }
      c = adaptive_order_check(all, s.order, name);
    } else {
      const auto error_at = [&](double h) -> std::optional<double> {
        system::TorusState x = p.scene.cardan_initial;
        if (!run_cardan_span(s, p.top, x, 0.0, t_end, h, 0.0, none).ok) return std::nullopt;
        return cardan_error(x, ref);
      };
      c = fixed_step_order_check(ladder_errors(s.order, error_at), s.order, name);
    }
    c.cardan = true;
    report.checks.push_back(std::move(c));
  }
  require_order_shown(s, report);
}

void cardan_symmetry_checks(const integrators::SchemeInfo& s, const Options& o, Report& report) {
  const auto& p = s.properties;
  for (const char* name : order_scenes) {
    const CardanProblem pr = load_cardan_problem(o.scenes_dir, name);
    if (p.symmetric && !p.adaptive) {
      const std::optional<double> e = cardan_symmetry_error(s, pr.top, pr.scene.cardan_initial, 0.05);
      std::ostringstream d;
      if (e) d << "|Phi_-h o Phi_h - id| (h = 0.05): " << *e << " (bound " << symmetry_bound << ")";
      else d << "a step failed";
      report.checks.push_back(cardan_check("symmetry", name, e && *e <= symmetry_bound, d.str()));
    }
    if (p.symplectic && !p.adaptive) {
      const std::optional<double> e = cardan_symplecticity_error(s, pr.top, pr.scene.cardan_initial, 0.2);
      std::ostringstream d;
      if (e)
        d << "|A^T S A - S|_max (h = 0.2, A by central differences): " << *e << " (bound " << symplecticity_bound
          << ")";
      else d << "a step failed";
      report.checks.push_back(cardan_check("symplectic", name, e && *e <= symplecticity_bound, d.str()));
    }
  }
}

void cardan_conservation_checks(const integrators::SchemeInfo& s, const Options& o, Report& report) {
  const auto& p = s.properties;
  const double h = 0.01;
  for (const char* name : {"cardan_general_horizontal", "cardan_general_asymmetric_up"}) {
    const CardanProblem pr = load_cardan_problem(o.scenes_dir, name);
    CardanDrift drift(pr.top);
    std::vector<std::pair<std::string, const double*>> claims;
    if (p.conserves_energy) claims.emplace_back("conserves energy", &drift.energy);
    if (p.conserves_vertical_momentum && pr.top.outer_angle_cyclic()) claims.emplace_back("conserves p1", &drift.p1);
    if (claims.empty()) continue;
    system::TorusState x = pr.scene.cardan_initial;
    const double tol = p.adaptive ? 1e-8 : 0.0;
    const integrators::RunStats st =
        run_cardan_span(s, pr.top, x, 0.0, static_cast<double>(o.conservation_steps) * h, h, tol, drift);
    for (const auto& [claim, value] : claims) {
      std::ostringstream d;
      d << "relative drift " << *value << " over " << (p.adaptive ? st.steps : o.conservation_steps)
        << (p.adaptive ? " steps at tol 1e-8" : " steps") << " (bound " << conservation_bound << ")"
        << (st.ok ? "" : "; the run failed: " + st.status);
      report.checks.push_back(cardan_check(claim, name, st.ok && *value <= conservation_bound, d.str()));
    }
  }
}

void cardan_allocation_checks(const integrators::SchemeInfo& s, const Options& o, Report& report) {
  if (!o.allocation_count) return;
  for (const char* name : order_scenes) {
    const CardanProblem pr = load_cardan_problem(o.scenes_dir, name);
    const double h = 1e-3;
    auto allocations_of = [&](std::int64_t steps, bool& ok) {
      system::TorusState x = pr.scene.cardan_initial;
      integrators::BasicNullObserver<system::TorusState> none;
      const double tol = s.properties.adaptive ? 1e-8 : 0.0;
      const long before = o.allocation_count();
      ok = run_cardan_span(s, pr.top, x, 0.0, static_cast<double>(steps) * h, h, tol, none).ok && ok;
      return o.allocation_count() - before;
    };
    bool ok = true;
    const long few = allocations_of(10, ok), many = allocations_of(1000, ok);
    report.checks.push_back(cardan_check("no allocation per step", name, ok && few == many,
                                         std::to_string(few) + " allocations in a run of 10 steps, " +
                                             std::to_string(many) + " in one of 1000" +
                                             (ok ? "" : "; a run failed")));
  }
}

}  // namespace

double cardan_error(const system::TorusState& x, const system::TorusState& reference) {
  const system::Vec6 a = system::stack(x), r = system::stack(reference);
  return ((a - r).array().abs() / (1.0 + r.array().abs())).maxCoeff();
}

CardanProblem load_cardan_problem(const std::string& scenes_dir, const std::string& name) {
  CardanProblem p{name, read_scene(scenes_dir + "/" + name + ".toml"), {}};
  p.top = cardan_top(p.scene);
  return p;
}

integrators::RunStats run_cardan_span(const integrators::SchemeInfo& scheme, const system::CardanTop& top,
                                      system::TorusState& x, double t0, double t_end, double h, double tol,
                                      integrators::TorusObserver& observer) {
  integrators::TorusRunConfig cfg;
  cfg.t0 = t0;
  cfg.t_end = t_end;
  cfg.dt = h;
  cfg.tol = tol;
  cfg.cpu_clock = false;
  cfg.save_every = 1;
  integrators::RunStats st;
  if (!scheme.run_cardan) {
    st.ok = false;
    st.status = "the scheme has no run function on T^3 x R^3 (run_cardan)";
    return st;
  }
  try {
    st = scheme.run_cardan(top, x, cfg, observer);
  } catch (const std::exception& e) {
    st.ok = false;
    st.status = e.what();
  }
  return st;
}

std::optional<double> cardan_symmetry_error(const integrators::SchemeInfo& scheme, const system::CardanTop& top,
                                            const system::TorusState& x0, double h) {
  integrators::BasicNullObserver<system::TorusState> none;
  system::TorusState x = x0;
  if (!run_cardan_span(scheme, top, x, 0.0, h, h, 0.0, none).ok) return std::nullopt;
  if (!run_cardan_span(scheme, top, x, h, 0.0, h, 0.0, none).ok) return std::nullopt;
  return cardan_error(x, x0);
}

std::optional<double> cardan_symplecticity_error(const integrators::SchemeInfo& scheme, const system::CardanTop& top,
                                                 const system::TorusState& x0, double h) {
  constexpr double delta = 1e-6;
  integrators::BasicNullObserver<system::TorusState> none;
  system::Mat6 A;
  const system::Vec6 y = system::stack(x0);
  for (int j = 0; j < 6; ++j) {
    system::TorusState plus = system::unstack(y + delta * system::Vec6::Unit(j));
    system::TorusState minus = system::unstack(y - delta * system::Vec6::Unit(j));
    if (!run_cardan_span(scheme, top, plus, 0.0, h, h, 0.0, none).ok) return std::nullopt;
    if (!run_cardan_span(scheme, top, minus, 0.0, h, h, 0.0, none).ok) return std::nullopt;
    A.col(j) = (system::stack(plus) - system::stack(minus)) / (2.0 * delta);
  }
  system::Mat6 S = system::Mat6::Zero();
  S.topRightCorner<3, 3>().setIdentity();
  S.bottomLeftCorner<3, 3>() = -lie::Mat3::Identity();
  return (A.transpose() * S * A - S).cwiseAbs().maxCoeff();
}

void CardanDrift::observe(std::int64_t, double, const system::TorusState& x) {
  const CardanInvariants::Values v = invariants_.evaluate(x);
  if (!started_) {
    first_ = v;
    started_ = true;
    return;
  }
  energy = std::max(energy, system::relative_error(v.energy, first_.energy));
  p1 = std::max(p1, system::relative_error(v.p1, first_.p1));
}

void cardan_checks(const integrators::SchemeInfo& scheme, const Options& options, Report& report) {
  cardan_order_checks(scheme, options, report);
  cardan_symmetry_checks(scheme, options, report);
  cardan_conservation_checks(scheme, options, report);
  cardan_allocation_checks(scheme, options, report);
}

}  // namespace lgi::experiments::verification

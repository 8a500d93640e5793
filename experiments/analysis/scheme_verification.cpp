// The verification kit's checks (scheme_verification.hpp states them and their bounds).
#include "experiments/analysis/scheme_verification.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <ostream>
#include <sstream>

#include "experiments/analysis/reference_solution.hpp"
#include "experiments/analysis/scheme_verification_cardan.hpp"
#include "experiments/io/scene_reader.hpp"
#include "integrators/system/free_body_exact.hpp"
#include "integrators/system/invariants.hpp"

namespace lgi::experiments::verification {
namespace {

constexpr double floor_error = 1e-10;  // compositions of 17 substeps reach round-off near 1e-12
constexpr double ceiling_error = 1e-2;
constexpr std::size_t fitted_points = 5;

struct Problem {
  std::string name;
  system::Scene scene;
  system::AnyModel model;
  system::State reference{};
  double t_end = 0.0;
  bool has_torque = false;
};

system::Scene load(const Options& o, const std::string& name) {
  return read_scene(o.scenes_dir + "/" + name + ".toml");
}

std::vector<Problem> order_problems(const Options& o) {
  std::vector<Problem> out;
  Problem free{"free_body_hlw", load(o, "free_body_hlw"), {}, {}, 10.0, false};
  free.model = system::make_model(free.scene);
  free.reference =
      system::FreeBodyExactFlow(std::get<system::FreeBody>(free.model).inertia, free.scene.initial).at(free.t_end);
  out.push_back(std::move(free));
  system::Scene driven = load(o, "general_top_richter");
  driven.declared<system::HarmonicDriveTerm>() =
      system::HarmonicDriveTerm::Parameters{lie::Vec3(0.3, -0.2, 0.1), 2.0, 0.3};
  std::pair<std::string, system::Scene> tops[] = {{"kovalevskaya", load(o, "kovalevskaya")},
                                                  {"driven general top", std::move(driven)}};
  for (auto& [name, scene] : tops) {
    Problem p{name, std::move(scene), {}, {}, 5.0, true};
    p.model = system::make_model(p.scene);
    p.reference = compute_reference(p.scene, p.model, p.t_end).state;
    out.push_back(std::move(p));
  }
  return out;
}

bool runs_on(const integrators::SchemeInfo& s, const system::AnyModel& m) {
  return integrators::unsupported_reason(s, m).empty();
}

double error_of(const system::State& s, const system::State& ref) { return global_error(s, ref).max; }

std::string format_points(const std::vector<ConvergencePoint>& pts) {
  std::ostringstream o;
  o.precision(3);
  for (const auto& p : pts) o << " (" << p.h << ", " << p.error << ")";
  return o.str();
}

Check order_check_fixed(const integrators::SchemeInfo& s, const Problem& p, int order) {
  return fixed_step_order_check(fixed_step_errors(s, p.model, p.scene.initial, p.reference, p.t_end, order), order,
                                p.name);
}

Check order_check_adaptive(const integrators::SchemeInfo& s, const Problem& p, int order) {
  std::vector<ConvergencePoint> all;
  for (double tol = 1e-3; tol >= 1e-13; tol /= std::sqrt(10.0)) {
    const RunResult r = run_once(s, p.model, p.scene.initial, make_config(p.t_end, std::nullopt, tol));
    if (!r.stats.ok || r.stats.steps == 0) continue;
    all.push_back({p.t_end / static_cast<double>(r.stats.steps), error_of(r.final, p.reference)});
  }
  return adaptive_order_check(all, order, p.name);
}

void order_checks(const integrators::SchemeInfo& s, const Options& o, Report& report) {
  if (s.order == 0) return;  // exact flows and variable-order extrapolation state no order
  for (const Problem& p : order_problems(o)) {
    if (!runs_on(s, p.model)) continue;
    const int order = p.has_torque && s.order_with_torque ? s.order_with_torque : s.order;
    report.checks.push_back(s.properties.adaptive ? order_check_adaptive(s, p, order)
                                                  : order_check_fixed(s, p, order));
  }
  require_order_shown(s, report);
}

void symmetry_checks(const integrators::SchemeInfo& s, const Options& o, Report& report) {
  const std::pair<const char*, double> cases[] = {
      {"free_body_hlw", 0.05}, {"heavy_top_trindade_1", 1e-3}, {"kovalevskaya", 0.05}};
  for (const auto& [name, h] : cases) {
    const system::Scene scene = load(o, name);
    const system::AnyModel model = system::make_model(scene);
    if (!runs_on(s, model)) continue;
    const RunResult forward = run_once(s, model, scene.initial, make_config(h, h, std::nullopt));
    integrators::RunConfig back = make_config(0.0, h, std::nullopt);
    back.t0 = h;
    const RunResult there_and_back = run_once(s, model, forward.final, back);
    const GlobalError e = global_error(there_and_back.final, scene.initial);
    Check c{"symmetry", name, forward.stats.ok && there_and_back.stats.ok && e.max <= 1e-13, {}};
    std::ostringstream d;
    d << "|Phi_-h o Phi_h - id|: attitude " << e.attitude << ", momentum " << e.momentum << " (bound 1e-13)";
    c.detail = d.str();
    report.checks.push_back(std::move(c));
  }
}

void conservation_checks(const integrators::SchemeInfo& s, const Options& o, Report& report) {
  const auto& p = s.properties;
  const std::pair<const char*, double> cases[] = {{"free_body_hlw", 0.01}, {"heavy_top_trindade_1", 1e-3}};
  for (const auto& [name, h] : cases) {
    const system::Scene scene = load(o, name);
    const system::AnyModel model = system::make_model(scene);
    if (!runs_on(s, model)) continue;
    const system::SceneInvariants inv(scene, model);
    std::vector<std::pair<std::string, const double*>> claims;
    InvariantDrift drift(inv);
    if (p.conserves_energy) claims.emplace_back("conserves energy", &drift.energy);
    if (inv.free_body() && p.conserves_momentum_norm) claims.emplace_back("conserves |Pi|", &drift.scalars[0]);
    if (inv.free_body() && p.conserves_spatial_momentum)
      claims.emplace_back("conserves spatial momentum", &drift.space_momentum);
    if (inv.heavy_top() && p.conserves_vertical_momentum) claims.emplace_back("conserves Pi.Gamma", &drift.scalars[0]);
    if (claims.empty()) continue;
    integrators::RunConfig cfg = make_config(static_cast<double>(o.conservation_steps) * h, h, std::nullopt);
    cfg.save_every = 1;
    system::State x = scene.initial;
    const integrators::RunStats stats = s.run(model, x, cfg, drift);
    for (const auto& [claim, value] : claims) {
      std::ostringstream d;
      d << "relative drift " << *value << " over " << o.conservation_steps << " steps (bound 1e-12)"
        << (stats.ok ? "" : "; the run failed: " + stats.status);
      report.checks.push_back({claim, name, stats.ok && *value <= 1e-12, d.str()});
    }
  }
}

void allocation_checks(const integrators::SchemeInfo& s, const Options& o, Report& report) {
  if (!o.allocation_count) return;
  for (const char* name : {"free_body_hlw", "heavy_top_trindade_1"}) {
    const system::Scene scene = load(o, name);
    const system::AnyModel model = system::make_model(scene);
    if (!runs_on(s, model)) continue;
    const double h = 1e-3;
    auto allocations_of = [&](std::int64_t steps, bool& ok) {
      system::State x = scene.initial;
      integrators::NullObserver none;
      integrators::RunConfig cfg = make_config(static_cast<double>(steps) * h, h, std::nullopt);
      if (s.properties.adaptive) cfg.tol = 1e-8;
      const long before = o.allocation_count();
      ok = s.run(model, x, cfg, none).ok && ok;
      return o.allocation_count() - before;
    };
    bool ok = true;
    const long few = allocations_of(10, ok), many = allocations_of(1000, ok);
    report.checks.push_back({"no allocation per step", name, ok && few == many,
                             std::to_string(few) + " allocations in a run of 10 steps, " + std::to_string(many) +
                                 " in one of 1000" + (ok ? "" : "; a run failed")});
  }
}

/// A claim no problem here could check is a failure, not a silent pass. On
/// T³ × ℝ³ "vertical momentum" is the cyclic p1 (scheme_facts.hpp), and
/// the Cardan top has no |Π| or spatial momentum integral: such claims fail.
void unchecked_claims(const integrators::SchemeInfo& s, Report& report) {
  auto checked = [&](const std::string& prefix) {
    return std::any_of(report.checks.begin(), report.checks.end(),
                       [&](const Check& c) { return c.name.rfind(prefix, 0) == 0; });
  };
  const auto& p = s.properties;
  const bool torus = s.support == integrators::SceneSupport::cardan_only;
  const std::pair<bool, const char*> claims[] = {
      {s.order > 0, "order"},
      {p.symmetric && !p.adaptive, "symmetry"},
      {torus && p.symplectic && !p.adaptive, "symplectic"},
      {p.conserves_energy, "conserves energy"},
      {p.conserves_momentum_norm, "conserves |Pi|"},
      {p.conserves_spatial_momentum, "conserves spatial momentum"},
      {p.conserves_vertical_momentum, torus ? "conserves p1" : "conserves Pi.Gamma"}};
  for (const auto& [claimed, name] : claims)
    if (claimed && !checked(name))
      report.checks.push_back({name, "-", false,
                               std::string("claimed, but no ") + (torus ? "Cardan " : "") +
                                   "problem of the kit supports the scheme or has this invariant"});
}

}  // namespace

std::vector<ConvergencePoint> ladder_errors(int order, const std::function<std::optional<double>(double)>& error_at) {
  const double ratio = std::max(std::pow(10.0, -1.0 / (2.0 * order)), 0.5);
  const double h0 = order >= 4 ? 1.0 : 0.2;
  const double h_min = order == 1 ? 5e-5 : 1e-3;
  std::vector<ConvergencePoint> all;
  for (double h = h0; h >= h_min; h *= ratio) {
    const std::optional<double> e = error_at(h);
    if (!e) continue;  // refused or failed at a coarse step
    all.push_back({h, *e});
    if (*e < floor_error) break;
  }
  return all;
}

std::vector<ConvergencePoint> fixed_step_errors(const integrators::SchemeInfo& scheme, const system::AnyModel& model,
                                                const system::State& initial, const system::State& reference,
                                                double t_end, int order) {
  return ladder_errors(order, [&](double h) -> std::optional<double> {
    const RunResult r = run_once(scheme, model, initial, make_config(t_end, h, std::nullopt));
    if (!r.stats.ok) return std::nullopt;
    return error_of(r.final, reference);
  });
}

Check fixed_step_order_check(const std::vector<ConvergencePoint>& all, int order, std::string problem) {
  const SlopeFit fit = fit_finest(all);
  Check c{"order " + std::to_string(order), std::move(problem), false, {}};
  const bool exact = !all.empty() && fit.points == 0 &&
                     std::all_of(all.begin(), all.end(), [](const auto& pt) { return pt.error < floor_error; });
  std::ostringstream d;
  if (exact) {
    c.passed = true;
    d << "exact: every error below " << floor_error;
  } else {
    const OrderVerdict v = order_verdict(fit, all, order);
    c.passed = v != OrderVerdict::not_shown;
    if (v == OrderVerdict::pre_asymptotic) d << "pre-asymptotic down to the floor " << floor_error << ", ";
    d << "slope " << fit.slope << " from " << fit.points << " points;" << format_points(all);
  }
  c.detail = d.str();
  return c;
}

Check adaptive_order_check(const std::vector<ConvergencePoint>& all, int order, std::string problem) {
  const SlopeFit fit = fit_finest(all);
  Check c{"order " + std::to_string(order) + " (adaptive, against the mean step)", std::move(problem), false, {}};
  c.passed = fit.points >= 3 && fit.slope >= order - std::max(0.5, 0.15 * order) &&
             (order > 5 || fit.slope <= order + std::max(0.5, 0.25 * order));
  std::ostringstream d;
  d << "slope " << fit.slope << " from " << fit.points << " points;" << format_points(all);
  c.detail = d.str();
  return c;
}

void require_order_shown(const integrators::SchemeInfo& s, Report& report) {
  // A fixed-step order must be shown somewhere, not only be pre-asymptotic everywhere.
  if (s.order == 0 || s.properties.adaptive) return;
  const bool shown = std::any_of(report.checks.begin(), report.checks.end(), [](const Check& c) {
    return c.name.starts_with("order") && c.passed && !c.detail.starts_with("pre-asymptotic");
  });
  if (!shown)
    report.checks.push_back({"order " + std::to_string(s.order), "-", false,
                             "not shown on any problem (pre-asymptotic or unsupported everywhere)"});
}

OrderVerdict order_verdict(const SlopeFit& fit, const std::vector<ConvergencePoint>& points, int order) {
  const double band = std::max(0.25, 0.05 * order);
  if (fit.points < 3) return OrderVerdict::not_shown;
  if (std::abs(fit.slope - order) <= band) return OrderVerdict::shown;
  const bool reached_floor = !points.empty() && points.back().error < floor_error;
  return fit.slope > order + band && reached_floor ? OrderVerdict::pre_asymptotic : OrderVerdict::not_shown;
}

SlopeFit fit_finest(const std::vector<ConvergencePoint>& points) {
  std::vector<ConvergencePoint> usable;
  for (const auto& pt : points)
    if (pt.error > floor_error && pt.error < ceiling_error) usable.push_back(pt);
  if (usable.size() > fitted_points)
    usable.erase(usable.begin(), usable.end() - static_cast<std::ptrdiff_t>(fitted_points));
  return fitted_slope(usable, floor_error, ceiling_error);
}

void InvariantDrift::observe(std::int64_t, double, const system::State& s) {
  const auto v = invariants_.evaluate(s);
  if (!started_) {
    first_ = v;
    started_ = true;
    return;
  }
  energy = std::max(energy, system::relative_error(v.energy, first_.energy));
  for (std::size_t k = 0; k < invariants_.scalar_names().size(); ++k)
    scalars[k] = std::max(scalars[k], system::relative_error(v.scalars[k], first_.scalars[k]));
  const double m0 = first_.space_momentum.norm();
  if (m0 > 0) space_momentum = std::max(space_momentum, (v.space_momentum - first_.space_momentum).norm() / m0);
}

SlopeFit fitted_slope(const std::vector<ConvergencePoint>& points, double floor, double ceiling) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (const auto& p : points) {
    if (!(p.error > floor && p.error < ceiling)) continue;
    const double x = std::log(p.h), y = std::log(p.error);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    ++n;
  }
  SlopeFit f;
  f.points = n;
  if (n >= 2) f.slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  return f;
}

bool Report::passed() const {
  return !checks.empty() && std::all_of(checks.begin(), checks.end(), [](const Check& c) { return c.passed; });
}

Report verify_scheme(const integrators::SchemeInfo& scheme, const Options& options) {
  Report report{scheme.name, integrators::state_space_name(scheme), {}};
  if (scheme.support == integrators::SceneSupport::cardan_only) {
    cardan_checks(scheme, options, report);  // the Cardan problems (scheme_verification_cardan.hpp)
  } else {
    order_checks(scheme, options, report);
    if (scheme.properties.symmetric && !scheme.properties.adaptive) symmetry_checks(scheme, options, report);
    conservation_checks(scheme, options, report);
    allocation_checks(scheme, options, report);
  }
  unchecked_claims(scheme, report);
  return report;
}

void print_report(std::ostream& out, const Report& report) {
  out << "verification of " << report.scheme << " (" << report.state_space << ")\n";
  for (const Check& c : report.checks)
    out << "  " << (c.passed ? "pass" : "FAIL") << "  " << c.name << " on " << c.problem
        << (c.cardan ? " [Cardan top, T^3 x R^3]" : "") << ": " << c.detail << '\n';
  out << (report.passed() ? "  every stated fact holds\n" : "  some stated facts do not hold\n");
}

}  // namespace lgi::experiments::verification

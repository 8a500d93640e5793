// The stress runner: a scheme's registry RunFunction with an observer that
// tracks the invariant errors and the CPU budget → outcome and error → pass.
#include "experiments/commands/stress/stress_runner.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "experiments/io/trajectory_observer.hpp"  // interrupt_requested
#include "integrators/system/free_body_exact.hpp"
#include "integrators/system/invariants.hpp"
#include "lie/so3.hpp"

namespace lgi::experiments::stress {

using integrators::SchemeInfo;

namespace {

std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

struct BudgetExceeded : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Tracks the largest invariant error over a run (docs/conventions.md §7: relative to
/// the initial value, absolute where it is 0; the orthogonality error |RᵀR − I|
/// as it is), keeps the latest state, and stops a run past its CPU budget or
/// on SIGINT/SIGTERM.
class StressObserver final : public integrators::Observer {
 public:
  StressObserver(const system::SceneInvariants& invariants, double budget_seconds)
      : inv_(invariants), cpu0_(integrators::detail::cpu_now()), budget_(budget_seconds) {}

  void observe(std::int64_t step, double t, const State& s) override {
    const system::InvariantValues v = inv_.evaluate(s);
    if (!have_initial_) {
      initial_ = v;
      have_initial_ = true;
    }
    if (inv_.energy_conserved()) note("energy", system::relative_error(v.energy, initial_.energy));
    const auto& names = inv_.scalar_names();
    for (std::size_t k = 0; k < names.size(); ++k)
      note(names[k].c_str(), system::relative_error(v.scalars[k], initial_.scalars[k]));
    if (inv_.free_body()) {
      const double m0 = initial_.space_momentum.norm();
      const double d = (v.space_momentum - initial_.space_momentum).norm();
      note("angular_momentum_space", m0 > 0.0 ? d / m0 : d);
    }
    note("orthogonality_error", v.orthogonality_error);
    max_momentum_ = std::max(max_momentum_, s.Pi.norm());
    last_ = s;
    last_t_ = t;
    last_step_ = step;
    have_last_ = true;
    if ((++samples_ & 63u) == 0) check();
  }

  double max_error() const { return max_; }
  double max_momentum() const { return max_momentum_; }
  std::string max_name() const { return max_name_ ? max_name_ : ""; }
  bool has_state() const { return have_last_; }
  const State& last_state() const { return last_; }
  double last_time() const { return last_t_; }
  std::int64_t last_step() const { return last_step_; }

 private:
  // `name` points at a string literal or into SceneInvariants::scalar_names(): no allocation per step.
  void note(const char* name, double e) {
    if (std::isnan(max_)) return;  // a NaN stays
    if (std::isnan(e) || e > max_) {
      max_ = e;
      max_name_ = name;
    }
  }
  void check() const {
    const double used = integrators::detail::cpu_now() - cpu0_;
    if (used > budget_)
      throw BudgetExceeded("stopped after " + fmt(used, 3) + " s CPU (the suite's per-run budget, --budget " +
                           fmt(budget_, 3) + " s) at step " + std::to_string(last_step_) + ", t = " + fmt(last_t_, 6));
  }

  const system::SceneInvariants& inv_;
  double cpu0_, budget_;
  bool have_initial_ = false, have_last_ = false;
  system::InvariantValues initial_{};
  double max_ = 0.0;
  const char* max_name_ = nullptr;
  double max_momentum_ = 0.0;
  State last_{};
  double last_t_ = 0.0;
  std::int64_t last_step_ = 0;
  std::uint64_t samples_ = 0;
};

}  // namespace

const char* outcome_name(Outcome o) {
  switch (o) {
    case Outcome::ok: return "ok";
    case Outcome::refused: return "refused";
    case Outcome::failed: return "failed";
  }
  return "?";
}

namespace {

struct RunResult {
  Outcome outcome = Outcome::ok;
  std::string reason;
  bool have_state = false;
  State state;
  double t_final = 0.0;
  double max_invariant_error = nan;
  std::string max_invariant;
  double max_momentum = 0.0;  // the largest |Π| observed
  double cpu_seconds = 0.0;
  std::int64_t steps = 0, rejected_steps = 0, rhs_evaluations = 0;
};

/// Refused or failed, from the reason a run stopped (STRESS.md, "Outcomes").
/// A step refused by design says so in its status (StepStatus::reason):
/// "step refused: ..." (a Cayley step that would turn by pi or more, a
/// modified inertia that is not positive).
Outcome classify_stop(const std::string& status) {
  if (status.rfind("Euler-angle singularity", 0) == 0) return Outcome::refused;  // a chart that will not go on
  if (status.rfind("step refused", 0) == 0) return Outcome::refused;
  if (status.find("needs a free body") != std::string::npos || status.find("needs torques") != std::string::npos)
    return Outcome::refused;
  return Outcome::failed;  // blow-up, a solve that did not converge, step-size collapse, anything else
}

RunResult run_scheme(const SchemeInfo& scheme, const Scene& scene, double t_end, double dt, double tol,
                     double first_step, double budget) {
  RunResult r;
  const system::AnyModel model = system::make_model(scene);
  if (std::string why = integrators::unsupported_reason(scheme, model); !why.empty()) {
    r.outcome = Outcome::refused;
    r.reason = why;
    return r;
  }
  const system::SceneInvariants invariants(scene, model);
  integrators::RunConfig cfg;
  cfg.t0 = 0.0;
  cfg.t_end = t_end;
  cfg.save_every = 1;
  cfg.stop = &interrupt_requested;  // the suite stops after this run (stress_command.cpp, run_suite)
  if (scheme.properties.adaptive) {
    cfg.tol = tol;
    cfg.dt = first_step;
  } else {
    cfg.dt = dt;
  }
  StressObserver observer(invariants, budget);
  State state = scene.initial;
  const double cpu0 = integrators::detail::cpu_now();
  integrators::RunStats stats;
  bool have_stats = false;
  try {
    stats = scheme.run(model, state, cfg, observer);
    have_stats = true;
  } catch (const BudgetExceeded& e) {
    r.outcome = Outcome::failed;
    r.reason = e.what();
  } catch (const std::exception& e) {
    r.outcome = Outcome::failed;
    r.reason = std::string("exception: ") + e.what();
  }
  r.cpu_seconds = have_stats ? stats.cpu_seconds : integrators::detail::cpu_now() - cpu0;
  r.max_invariant_error = observer.max_error();
  r.max_invariant = observer.max_name();
  r.max_momentum = observer.max_momentum();
  if (observer.has_state()) {
    r.have_state = true;
    r.state = observer.last_state();
    r.t_final = observer.last_time();
  }
  r.steps = have_stats ? stats.steps : observer.last_step();
  if (have_stats) {
    r.rejected_steps = stats.work.rejected_steps;
    r.rhs_evaluations = stats.work.rhs_evaluations;
    if (!stats.ok) {
      r.outcome = classify_stop(stats.status);
      r.reason = stats.status;
    }
  }
  r.reason = one_line(r.reason);
  return r;
}

// ---- errors -----------------------------------------------------------------------------

/// The rotation nearest to R (polar factor), so that baselines whose matrix
/// or quaternion has drifted off SO(3) get an attitude error that means
/// something; the drift itself is in the invariant errors.
Mat3 nearest_rotation(const Mat3& R) {
  Eigen::JacobiSVD<Mat3> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 U = svd.matrixU();
  const Mat3 V = svd.matrixV();
  if ((U * V.transpose()).determinant() < 0.0) U.col(2) *= -1.0;
  return U * V.transpose();
}

struct StateError {
  double attitude = nan, momentum = nan, total = nan;
};

/// The geodesic angle (docs/conventions.md §7) and |Π/unit − Π_ref| / scale, where scale is the
/// largest |Π| along the reference trajectory (STRESS.md: docs/conventions.md's |Π_ref(t_end)| is
/// ill-conditioned where the reference passes near Π = 0, e.g. a pendulum's turning point).
StateError state_error(const State& s, const State& ref, double scale, double unit = 1.0) {
  StateError e;
  if (!s.R.allFinite() || !s.Pi.allFinite()) {
    e.attitude = e.momentum = e.total = inf;
    return e;
  }
  e.attitude = s.R == ref.R ? 0.0 : lie::geodesic_distance(ref.R, nearest_rotation(s.R));
  const Vec3 p = s.Pi / unit;
  e.momentum = scale > 0.0 ? (p - ref.Pi).norm() / scale : (p - ref.Pi).norm();
  e.total = std::max(e.attitude, e.momentum);
  if (std::isnan(e.total)) e.total = inf;
  return e;
}

}  // namespace

// ---- references -------------------------------------------------------------------------

void compute_reference(Variant& v, double budget) {
  Reference& ref = v.reference;
  if (v.units) {
    ref.kind = "same scheme in SI units";
    ref.check = "the row's error is the relative disagreement between the rescaled run (mapped back to SI) and the "
                "SI run";
    return;
  }
  if (v.t_end == 0.0) {
    ref.kind = "initial state";
    ref.available = true;
    ref.state = v.scene.initial;
    ref.momentum_scale = v.scene.initial.Pi.norm();
    ref.estimated_error = 0.0;
    ref.check = "exact";
    return;
  }
  const SchemeInfo* dp54 = integrators::find_scheme("rkmk-dp54");
  auto converged = [&](double tol, std::string& why) -> std::optional<RunResult> {
    if (!dp54) {
      why = "rkmk-dp54 is not registered";
      return std::nullopt;
    }
    const RunResult r = run_scheme(*dp54, v.scene, v.t_end, 0.0, tol, 0.0, 20.0 * budget);
    if (r.outcome != Outcome::ok || !r.have_state) {
      why = "rkmk-dp54 at tol " + fmt(tol, 3) + ": " + r.reason;
      return std::nullopt;
    }
    return r;
  };
  if (v.scene.is_free_body()) {
    ref.kind = "exact";
    ref.scheme = "FreeBodyExactFlow";
    const system::FreeBodyExactFlow flow(system::make_inertia(v.scene.inertia), v.scene.initial);
    ref.state = flow.at(v.t_end);
    ref.momentum_scale = v.scene.initial.Pi.norm();  // |Π| is an invariant
    ref.available = ref.state.R.allFinite() && ref.state.Pi.allFinite();
    if (!ref.available) ref.failure = "the exact flow returned a non-finite state";
    std::string why;
    if (const auto check = converged(1e-12, why)) {
      ref.estimated_error = state_error(check->state, ref.state, ref.momentum_scale).total;
      ref.check = "disagreement with rkmk-dp54 at tol 1e-12 (an upper bound on the exact flow's error, "
                  "dominated by rkmk-dp54's)";
    } else {
      ref.check = "no cross-check: " + why;
    }
    return;
  }
  ref.kind = "converged";
  ref.scheme = "rkmk-dp54";
  ref.tol = 1e-12;
  std::string why;
  const auto fine = converged(1e-12, why);
  if (!fine) {
    ref.failure = why;
    return;
  }
  ref.state = fine->state;
  ref.momentum_scale = fine->max_momentum;
  ref.available = true;
  std::string why2;
  if (const auto coarse = converged(1e-11, why2)) {
    ref.estimated_error = state_error(coarse->state, ref.state, ref.momentum_scale).total;
    ref.check = "disagreement with rkmk-dp54 at tol 1e-11 (an overestimate of the error at 1e-12)";
  } else {
    ref.check = "no estimate: " + why2;
  }
}

// ---- rows ---------------------------------------------------------------------------------

namespace {


bool evaluate_pass(const Row& row, const Criterion& c, const SchemeInfo& scheme) {
  switch (row.outcome) {
    case Outcome::refused: return !row.reason.empty();
    case Outcome::failed: return c.failure_passes && !row.reason.empty();
    case Outcome::ok: break;
  }
  if (!std::isfinite(row.error) || !std::isfinite(row.max_invariant_error)) return false;
  if (c.zero_time) return row.steps == 0 && row.error <= c.max_error;
  if (c.fixed_one_step && !scheme.properties.adaptive && row.steps != 1) return false;
  if (c.invariants_only) return row.max_invariant_error <= c.max_error;
  return row.error <= c.max_error;
}

}  // namespace

Row run_row(const Variant& v, const SchemeInfo& scheme, double budget) {
  Row row;
  row.case_id = v.case_id;
  row.variant = v.variant;
  row.scheme = scheme.name;
  row.t_end = v.t_end;
  if (scheme.properties.adaptive) {
    row.tol = v.tol;
    if (v.first_step > 0.0) row.dt = v.first_step;
  } else {
    row.dt = v.dt;
  }
  row.reference = v.reference.kind;
  row.state_judged = !v.criterion.invariants_only;
  if (v.reference.kind == "converged")
    row.reference += " (" + v.reference.scheme + ", tol " + fmt(v.reference.tol, 3) + ")";

  // What a run reports in the row: the SI run's, or the rescaled run's for a units case.
  auto report_run = [&row](const RunResult& run) {
    row.outcome = run.outcome;
    row.reason = run.reason;
    row.max_invariant_error = run.max_invariant_error;
    row.max_invariant = run.max_invariant;
    row.cpu_seconds = run.cpu_seconds;
    row.steps = run.steps;
    row.rejected_steps = run.rejected_steps;
    row.rhs_evaluations = run.rhs_evaluations;
  };
  const RunResult r = run_scheme(scheme, v.scene, v.t_end, v.dt, v.tol, v.first_step, budget);
  report_run(r);

  if (v.units) {
    const UnitScale& u = v.scale;
    const double sT = u.time;
    const double sPi = u.mass * u.length * u.length / sT;
    const double dt = v.dt * sT, first = v.first_step * sT;
    const RunResult s = run_scheme(scheme, v.scaled, v.t_end * sT, dt, v.tol, first, budget);
    report_run(s);
    if (s.outcome != r.outcome) {
      row.outcome = s.outcome == Outcome::ok ? Outcome::failed : s.outcome;
      row.reason = "outcome differs from the SI run (rescaled: " + std::string(outcome_name(s.outcome)) +
                   (s.reason.empty() ? "" : ": " + s.reason) + "; SI: " + outcome_name(r.outcome) +
                   (r.reason.empty() ? "" : ": " + r.reason) + ")";
    } else if (s.outcome == Outcome::ok && r.have_state && s.have_state) {
      const StateError e = state_error(s.state, r.state, r.max_momentum, sPi);
      const double dt_rel = r.t_final != 0.0 ? std::abs(s.t_final / sT - r.t_final) / std::abs(r.t_final)
                                             : std::abs(s.t_final / sT - r.t_final);
      // Invariant errors are dimensionless already: their difference is compared as it is.
      const double inv_diff = std::abs(s.max_invariant_error - r.max_invariant_error);
      row.error_attitude = e.attitude;
      row.error_momentum = e.momentum;
      row.error = std::max({e.total, dt_rel, inv_diff});
      if (std::isnan(row.error)) row.error = inf;
    }
    row.pass = evaluate_pass(row, v.criterion, scheme) ? 1 : 0;
    return row;
  }

  if (r.outcome == Outcome::ok && r.have_state && v.reference.available) {
    const StateError e = state_error(r.state, v.reference.state, v.reference.momentum_scale);
    row.error = e.total;
    row.error_attitude = e.attitude;
    row.error_momentum = e.momentum;
  } else if (r.outcome == Outcome::ok && r.have_state && !v.reference.available) {
    row.error = nan;
  }
  row.pass = evaluate_pass(row, v.criterion, scheme) ? 1 : 0;
  return row;
}

}  // namespace lgi::experiments::stress

#pragma once
// What every scheme provides, and the work counters they fill.
//
// A fixed-step scheme is a class with
//   template <class Model> StepStatus step(const Model&, State&, double t, double h, WorkCounters&);
// and optionally
//   template <class Model> void start(const Model&, const State& initial, double t0);
// (per-run set-up, e.g. the exact flow's constants; it may return a
// StepStatus, refused if the scheme cannot start from that state). An
// adaptive scheme has
//   template <class Model> AdaptiveStatus attempt(const Model&, State&, double t, double h, WorkCounters&);
// which either accepts (advancing the state by h) or rejects, and proposes
// the next step in both cases, and
//   template <class Model> double initial_step(const Model&, const State&, double t, double span);
// for runs without a first trial step. Optional, for the baselines' charts
// (baselines/chart_scheme.hpp): interpolate(model, t, out) (dense output at
// output times inside a step), euler_angles() and interpolated_euler_angles()
// (Observer::observe_euler_zxz), refusal_reason() (StepStatus::refused).
// Optional, for a scheme whose loop state is its own variable rather than the
// trajectory's (a processed composition, processed_composition.hpp):
//   template <class Model> State observable(const Model&, const State& y, WorkCounters&) const;
// the trajectory's state for observers and for the run's end (stepper_loop.hpp);
// such a scheme locates no events (SchemeInfo::locates_events is false).
// Optional, for a scheme that keeps the attitude in its own form along a run
// (the preprocessed DMV on a free body: a quaternion, cayley_quaternion.hpp):
//   template <class Model> StepStatus step_keeping_attitude(const Model&, State&, double t, double h, WorkCounters&);
//   void write_attitude(State&) const;
// the first advances Π and the scheme's attitude and leaves s.R as it was;
// the second sets s.R from it. The loop writes R only where R is read
// (stepper_loop.hpp, "Kept attitude"); step() must be both, so that any
// other caller sees a complete state.
// Schemes never write files and never renormalise the attitude (a baseline
// chart that projects, quat-normalized, says so in its name).
//
// Resume (a run continued bit for bit from a saved step, RunConfig::
// checkpoints, run_config.hpp): a scheme whose step depends on nothing but
// the state, t and h (and what start() set up from the run's initial state)
// needs nothing saved. That holds when the step the loop takes is const
// (step() of a fixed-step scheme, attempt() of an adaptive one), or when the
// scheme states it:
//   static constexpr bool memoryless_steps = true;
// A scheme that carries something from one step to the next (a compensated
// sum's carry, an FSAL stage) saves and restores it:
//   void save_memory(std::vector<double>& out) const;  // appends its memory
//   bool restore_memory(std::span<const double> in);    // false: not a memory it saved
// Any other scheme cannot be resumed (SchemeInfo::resumable is false).
#include <concepts>
#include <cstdint>
#include <span>
#include <vector>

#include "integrators/core/scheme_facts.hpp"
#include "integrators/core/state_space.hpp"
#include "integrators/system/rigid_body.hpp"

namespace lgi::integrators {

using lie::Mat3;
using lie::Vec3;
using system::State;

/// Outcome of one step. Explicit schemes always converge; implicit ones
/// report their Newton iterations and final residual, and the stepper loop
/// stops the run (exit 1) on a step that did not converge.
struct StepStatus {
  bool converged = true;
  int iterations = 0;
  double residual = 0.0;
  /// Why a step that did not converge failed, if not simply "the implicit
  /// solve did not converge" (e.g. a step refused before any iteration
  /// because no solution of the scheme's equations approximates the flow).
  /// A string literal; it goes into the run's status message.
  const char* reason = nullptr;
  /// The scheme refused the step and left its state as it was before it
  /// (a chart that cannot be trusted beyond this point: the Euler-angle
  /// guard of the baselines, baselines/chart_scheme.hpp). The run stops with
  /// the scheme's refusal_reason(); the step counts as neither a step nor a
  /// Newton failure. start() may refuse the initial state the same way.
  bool refused = false;
};

struct AdaptiveStatus {
  bool accepted = false;
  double error_norm = 0.0;  // weighted error estimate, ≤ 1 on acceptance
  double h_next = 0.0;
  StepStatus solve{};
};

/// Counters written to /diagnostics for every scheme, so work compares like
/// for like: right-hand-side evaluations count calls of the model's
/// Euler–Poisson field (Ω and Π̇ at one stage).
struct WorkCounters {
  std::int64_t rhs_evaluations = 0;
  std::int64_t rejected_steps = 0;
  std::int64_t newton_iterations_max = 0;
  std::int64_t newton_failures = 0;
};

template <class Scheme>
concept saves_step_memory = requires(const Scheme& c, Scheme& s, std::vector<double>& out, std::span<const double> in) {
  c.save_memory(out);
  { s.restore_memory(in) } -> std::same_as<bool>;
};

namespace detail {
template <class Scheme>
concept declared_memoryless = requires { requires Scheme::memoryless_steps; };
template <class Scheme>
concept has_base_scheme = requires { typename Scheme::base_scheme_type; };
template <class Scheme, class Model>
concept const_step =
    requires(const Scheme& c, const Model& m, state_of<Model>& x, WorkCounters& w) { c.step(m, x, 0.0, 0.0, w); };
template <class Scheme, class Model>
concept const_attempt =
    requires(const Scheme& c, const Model& m, state_of<Model>& x, WorkCounters& w) { c.attempt(m, x, 0.0, 0.0, w); };
}  // namespace detail

/// Whether the fixed-step (Adaptive: the adaptive) loop can resume Scheme on
/// Model from a saved step (top of this file). A composition keeps what its
/// base keeps (composition.hpp: base_scheme_type, and the base's memory).
template <class Scheme, class Model, bool Adaptive>
constexpr bool resumable_scheme() {
  if constexpr (saves_step_memory<Scheme> || detail::declared_memoryless<Scheme>) return true;
  else if constexpr (detail::has_base_scheme<Scheme>)
    return resumable_scheme<typename Scheme::base_scheme_type, Model, false>();
  else if constexpr (Adaptive) return detail::const_attempt<Scheme, Model>;
  else return detail::const_step<Scheme, Model>;
}

}  // namespace lgi::integrators

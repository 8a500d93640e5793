#pragma once
// What every scheme provides, and the work counters they fill.
//
// A fixed-step scheme is a class with
//   template <class Model> StepStatus step(const Model&, State&, double t, double h, WorkCounters&);
// and optionally
//   template <class Model> void start(const Model&, const State& initial, double t0);
// (per-run set-up, e.g. the exact flow's constants). An adaptive scheme has
//   template <class Model> AdaptiveStatus attempt(const Model&, State&, double t, double h, WorkCounters&);
// which either accepts (advancing the state by h) or rejects, and proposes
// the next step in both cases. Schemes never write files and never
// renormalise the attitude.
#include <cstdint>

#include "integrators/scheme_facts.hpp"
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

}  // namespace lgi::integrators

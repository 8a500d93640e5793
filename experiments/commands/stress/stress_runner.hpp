#pragma once
// Running one scheme on one stress variant: its reference, the run under a
// CPU budget, the error against the reference and the pass of its criterion.
#include <cstdint>
#include <string>

#include "experiments/commands/stress/stress_suite.hpp"
#include "integrators/registry/registry.hpp"

namespace lgi::experiments::stress {

/// How a run ended (STRESS.md, "Outcomes").
enum class Outcome { ok, refused, failed };

const char* outcome_name(Outcome o);

/// One scheme on one variant: a row of /results.
struct Row {
  std::string case_id, variant, scheme;
  Outcome outcome = Outcome::ok;
  std::string reason;
  int pass = 0;
  double error = nan, error_attitude = nan, error_momentum = nan;
  double max_invariant_error = nan;
  std::string max_invariant;
  double cpu_seconds = nan;
  std::int64_t steps = -1, rejected_steps = -1, rhs_evaluations = -1;
  double dt = nan, tol = nan, t_end = nan;
  std::string reference;
  bool state_judged = true;  // false where the final state is ill-conditioned (Criterion::invariants_only)
};

/// Fills v.reference: exact, converged rkmk-dp54, the initial state, or the SI run (STRESS.md, "References").
void compute_reference(Variant& v, double budget);

/// Runs `scheme` on `v` (and on its rescaled scene for a units case) and judges it.
Row run_row(const Variant& v, const integrators::SchemeInfo& scheme, double budget);

}  // namespace lgi::experiments::stress

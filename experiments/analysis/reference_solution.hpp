#pragma once
// Reference solutions and the global error measure (docs/conventions.md §7),
// for the studies that compare a scheme's final state with a reference.
//
// Reference kinds (/reference in a work-precision file, RESULTS.md):
//   exact      the exact flow (system::FreeBodyExactFlow) at t_end. Its
//              estimated_error is the conditioning floor of the problem: the
//              spread of exact flows from initial states perturbed at
//              round-off, and the flow's own consistency under splitting
//              [0, T] in two. Near a separatrix it reaches 1e-7.
//   converged  rkmk-dop853 (adaptive RKMK of order 8; supports every model:
//              torques, damping, drives) at tol 1e-14; its error is
//              estimated by the distance to a run at tol 1e-13. That is about
//              the error of the coarser run: on the shipped scenes the pair's
//              error is proportional to tol (HLW's top: 6.9e-11, 6.3e-12,
//              5.9e-13 at tol 1e-10, 1e-11, 1e-12), so the estimate exceeds
//              the reference's own error about tenfold. Order 8 takes a tenth
//              of the steps of the 5(4) pair used before, with less round-off:
//              the estimates fell 2.4-20x (heavy_top_hlw 4.5e-13 -> 3.2e-14,
//              magnetic_top 4.3e-11 -> 2.1e-12), which resolves errors of
//              1e-10 on the long runs. If a run fails (step size collapse),
//              both tolerances are relaxed tenfold, up to 1e-12 / 1e-11.
#include <atomic>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "integrators/registry/registry.hpp"

namespace lgi::experiments {

/// The scheme of a "converged" reference (header comment).
inline constexpr const char* converged_reference_scheme = "rkmk-dop853";

struct GlobalError {
  double attitude = std::numeric_limits<double>::quiet_NaN();
  double momentum = std::numeric_limits<double>::quiet_NaN();
  double max = std::numeric_limits<double>::quiet_NaN();
};

/// docs/conventions.md §7: geodesic angle, relative momentum error, the larger (NaN for a non-finite state).
GlobalError global_error(const system::State& s, const system::State& ref);

/// One registered run from `initial` to cfg.t_end, observing only its final state.
struct RunResult {
  integrators::RunStats stats;
  system::State final{};
  bool threw = false;
};
RunResult run_once(const integrators::SchemeInfo& scheme, const system::AnyModel& model, const system::State& initial,
                   const integrators::RunConfig& cfg);

/// A run over [0, t_end] with a fixed step (dt) or a tolerance (tol), saving nothing in between.
integrators::RunConfig make_config(double t_end, std::optional<double> dt, std::optional<double> tol);

struct Reference {
  std::string kind;    // "exact" or "converged"
  std::string scheme;  // "exact" or the scheme's name
  double tol = std::numeric_limits<double>::quiet_NaN();
  double comparison_tol = std::numeric_limits<double>::quiet_NaN();
  double estimated_error = 0.0;
  double amplification = 0.0;  // exact references: spread at t_end per unit relative perturbation (κ)
  std::int64_t steps = -1;
  double cpu_seconds = std::numeric_limits<double>::quiet_NaN();
  system::State state{};
};

/// Thrown by compute_reference when `stop` ended one of its runs (a signal).
struct ReferenceInterrupted {};

/// The reference at t_end for a scene's model; throws RunError if no converged run can be had.
/// `stop`, if given, is read every step of its runs (RunConfig::stop): once set, ReferenceInterrupted.
Reference compute_reference(const system::Scene& scene, const system::AnyModel& model, double t_end,
                            const std::atomic<bool>* stop = nullptr);

/// The floor of one row: the reference's estimated error, or the round-off a
/// run of `steps` steps accumulates (one unit round-off a step, worst case,
/// amplified by κ, with a safety factor of 4), whichever is larger.
double row_floor(double reference_error, double amplification, std::int64_t steps);

}  // namespace lgi::experiments

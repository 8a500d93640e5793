#pragma once
// The verification kit: lgi's generic checks of a scheme's stated facts, run
// on any registered scheme, an out-of-tree one included (docs/extending.md,
// examples/custom_scheme/), on either state space: a scheme of SO(3) × ℝ³ on
// the problems below, a scheme of T³ × ℝ³ (support cardan_only, run_cardan)
// on the Cardan problems of scheme_verification_cardan.hpp, with the same
// step ladders, fits and bounds; the report names the state space and marks
// each Cardan problem. What it checks, from the scheme's SchemeInfo:
//  - order: fixed-step schemes, the slope of the global error
//    (docs/conventions.md §7) against h on problems whose stage fields do not
//    commute (a constant field would prove nothing): free_body_hlw against
//    the exact flow (t = 10), the Kovalevskaya top (a conservative torque)
//    and Richter's general top with a harmonic body-fixed drive (a
//    time-dependent torque: the stage times matter) against converged
//    references (analysis/reference_solution.hpp), t = 5. Steps
//    h_k = h0 r^k, r = max(10^(-1/(2p)), 1/2), h0 = 1 for p ≥ 4 else 0.2,
//    down to the 1e-10 floor or h_min (5e-5 for p = 1, else 1e-3); the slope
//    through the five finest points between 1e-10 and 1e-2 must be within
//    max(0.25, 0.05 p) of the stated p (order_with_torque where stated, on
//    the tops). A slope above that band on a problem where the steps reached
//    the floor is pre-asymptotic down to round-off (order_verdict): that
//    problem passes, and at least one other must show p. Adaptive schemes: the slope against the mean step T/steps as
//    tol falls by √10 from 1e-3 to 1e-13 (HNW I §II.4), at least
//    p − max(0.5, 0.15 p) and, for p ≤ 5, at most p + max(0.5, 0.25 p).
//  - symmetry, if claimed: Φ₋ₕ ∘ Φₕ = id to 1e-13 (attitude and relative
//    momentum) on a free body, a heavy top and the Kovalevskaya top.
//  - each claimed conservation (energy, |Π|, spatial momentum, Π·Γ):
//    relative drift ≤ 1e-12 over Options::conservation_steps steps on
//    free_body_hlw (h = 0.01) and heavy_top_trindade_1 (h = 1e-3).
//  - zero allocations per step: a run of 1000 steps allocates as often as
//    one of 10, on the same two scenes. Needs a counter of the program's
//    allocations (allocation_counter.hpp); without one it is not run.
// Every claim must be checked on at least one problem the scheme supports;
// a claim that none supports is a failed check, not a silent pass (on T³:
// |Π| and the spatial momentum, which the Cardan top does not conserve).
#include <array>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "integrators/registry/registry.hpp"
#include "integrators/system/invariants.hpp"

namespace lgi::experiments::verification {

struct Options {
  /// The shipped scenes (an installed lgi: <prefix>/share/lgi/scenes; the
  /// CMake package sets lgi_SCENES_DIR to it).
  std::string scenes_dir;
  /// The program's allocation count (allocation_counter.hpp's
  /// counted_allocations), or null: the allocation check is not run.
  long (*allocation_count)() = nullptr;
  std::int64_t conservation_steps = 20000;
};

struct Check {
  std::string name;     // "order", "symmetry", "conserves energy", ...
  std::string problem;  // the scene it ran on
  bool passed = false;
  std::string detail;   // what was measured against what was stated
  bool cardan = false;  // the problem is a Cardan top (T³ × ℝ³)
};

struct Report {
  std::string scheme;
  std::string state_space;  // integrators::state_space_name: "SO(3) x R^3" or "T^3 x R^3"
  std::vector<Check> checks;
  /// Every check passed, and there was at least one.
  bool passed() const;
};

Report verify_scheme(const integrators::SchemeInfo& scheme, const Options& options);

/// One line per check and a verdict.
void print_report(std::ostream& out, const Report& report);

// ---- building blocks, shared with lgi's own generic tests ------------------

struct ConvergencePoint {
  double h;
  double error;
};
struct SlopeFit {
  double slope = 0.0;
  int points = 0;
};
/// Least-squares slope of log(error) against log(h) over the points with
/// floor < error < ceiling (the round-off plateau and the pre-asymptotic
/// regime dropped).
SlopeFit fitted_slope(const std::vector<ConvergencePoint>& points, double floor, double ceiling);

/// error_at(h) at the steps of the order check for a stated order p (top of
/// this file), coarsest first, stopping below the 1e-10 floor; a step where
/// it returns nothing (a failed run, a refused coarse step) is left out.
std::vector<ConvergencePoint> ladder_errors(int order, const std::function<std::optional<double>(double)>& error_at);
/// The global errors at t_end of fixed-step runs of a scheme stating order p
/// on the ladder of ladder_errors().
std::vector<ConvergencePoint> fixed_step_errors(const integrators::SchemeInfo& scheme, const system::AnyModel& model,
                                                const system::State& initial, const system::State& reference,
                                                double t_end, int order);
/// The slope through the five finest points between the 1e-10 floor and 1e-2.
SlopeFit fit_finest(const std::vector<ConvergencePoint>& points);

/// What a fixed-step fit says of a stated order p: shown (≥ 3 points, slope
/// within max(0.25, 0.05 p) of p); pre-asymptotic (≥ 3 points, slope above
/// that band, and the steps went down to the floor: the asymptotic regime
/// lies at round-off, as for the processed compositions on the Kovalevskaya
/// top, whose leading error terms are small); or not shown. A pre-asymptotic
/// problem neither confirms nor refutes p; another problem must show it.
enum class OrderVerdict { shown, pre_asymptotic, not_shown };
OrderVerdict order_verdict(const SlopeFit& fit, const std::vector<ConvergencePoint>& points, int order);

/// The order check on one problem from the ladder's points (exact: every
/// error below the floor; else order_verdict), named "order p".
Check fixed_step_order_check(const std::vector<ConvergencePoint>& points, int order, std::string problem);
/// The adaptive order check from (mean step, error) points (top of this file).
Check adaptive_order_check(const std::vector<ConvergencePoint>& points, int order, std::string problem);
/// A fixed-step order must be shown on some problem, not be pre-asymptotic
/// (or unsupported) everywhere: else adds a failed "order p" check.
void require_order_shown(const integrators::SchemeInfo& scheme, Report& report);

/// The largest relative drift of each invariant of a scene from its value at
/// the first sample: the energy, the spatial momentum (|m − m0|/|m0|) and
/// the scalar invariants in SceneInvariants::scalar_names() order (|Π| for
/// a free body, Π·Γ for a heavy top, ...).
class InvariantDrift final : public integrators::Observer {
 public:
  explicit InvariantDrift(const system::SceneInvariants& invariants) : invariants_(invariants) {}
  void observe(std::int64_t step, double t, const system::State& s) override;
  double energy = 0.0;
  double space_momentum = 0.0;
  std::array<double, system::InvariantValues::capacity> scalars{};

 private:
  const system::SceneInvariants& invariants_;
  system::InvariantValues first_{};
  bool started_ = false;
};

}  // namespace lgi::experiments::verification

#pragma once
// The verification kit on T³ × ℝ³ (scheme_verification.hpp): the checks of
// a Cardan scheme's stated facts (support cardan_only, run through
// run_cardan), on shipped Cardan scenes (docs/cardan.md §9), with the SO(3)
// kit's step ladders, fits and verdicts. Every check is marked Check::cardan.
//  - order: on cardan_euler_tilted (no gravity, the body's symmetry axis
//    tilted in the gimbal: only q1 is cyclic) and cardan_general_horizontal
//    (Richter's general top, outer axis horizontal: M(q) and V(q) both vary,
//    H is not separable), t = cardan_order_t_end, against an independent
//    reference: Boost.Odeint's controlled runge_kutta_fehlberg78 on
//    x = (q, p) ∈ ℝ⁶ at tol 1e-14, sharing only CardanTop::field with the
//    code under test. Error: cardan_error.
//  - symmetry, if claimed: Φ₋ₕ ∘ Φₕ = id, cardan_error ≤ 1e-13, h = 0.05,
//    on both scenes.
//  - symplecticity, if claimed (canonical coordinates: checkable on T³):
//    the step map's Jacobian A (central differences, δ = 1e-6) satisfies
//    |AᵀSA − S|_max ≤ 1e-7 at h = 0.2 on both scenes (the midpoint
//    rule: 4e-10; RK4, not symplectic: 7e-4 and 1e-5).
//  - energy, if claimed: relative drift ≤ 1e-12 over
//    Options::conservation_steps steps of h = 0.01 on
//    cardan_general_horizontal and cardan_general_asymmetric_up (gravity,
//    massive rings).
//  - p1, if claimed (conserves_vertical_momentum on T³: the momentum of the
//    outer angle, an integral where the outer axis is vertical,
//    CardanTop::outer_angle_cyclic): relative drift ≤ 1e-12 the same way on
//    cardan_general_asymmetric_up (tilt 0, gravity); never where p1 is no
//    integral (the horizontal axis).
//  - zero allocations per step: 10 against 1000 steps of h = 1e-3 on the two
//    order scenes (with Options::allocation_count).
#include <cstdint>
#include <optional>
#include <string>

#include "experiments/analysis/cardan_invariants.hpp"
#include "experiments/analysis/scheme_verification.hpp"
#include "integrators/system/cardan.hpp"
#include "integrators/system/scene.hpp"

namespace lgi::experiments::verification {

inline constexpr double cardan_order_t_end = 2.0;

/// The distance of two Cardan states, max_i |x_i − r_i| / (1 + |r_i|) over
/// x = (q, p), the angles unwrapped (no chart: T³ is abelian).
double cardan_error(const system::TorusState& x, const system::TorusState& reference);

/// A shipped Cardan scene (with [suspension]) and its model.
struct CardanProblem {
  std::string name;
  system::Scene scene;
  system::CardanTop top;
};
CardanProblem load_cardan_problem(const std::string& scenes_dir, const std::string& name);

/// A fixed-step run (tol = 0), or an adaptive one at tol, of a T³ scheme
/// from t0 to t_end; x becomes the final state. A throw is a failed run.
integrators::RunStats run_cardan_span(const integrators::SchemeInfo& scheme, const system::CardanTop& top,
                                      system::TorusState& x, double t0, double t_end, double h, double tol,
                                      integrators::TorusObserver& observer);

/// cardan_error(Φ₋ₕ(Φₕ(x0)), x0); nothing if a step failed.
std::optional<double> cardan_symmetry_error(const integrators::SchemeInfo& scheme, const system::CardanTop& top,
                                            const system::TorusState& x0, double h);

/// |AᵀSA − S|_max for the Jacobian A of one step of h from x0; nothing if a step failed.
std::optional<double> cardan_symplecticity_error(const integrators::SchemeInfo& scheme, const system::CardanTop& top,
                                                 const system::TorusState& x0, double h);

/// The largest relative drift of the Cardan invariants (CardanInvariants,
/// system::relative_error) from the first sample: H, rings included, and p1
/// (meaningful where top.outer_angle_cyclic()).
class CardanDrift final : public integrators::TorusObserver {
 public:
  explicit CardanDrift(const system::CardanTop& top) : invariants_(top) {}
  void observe(std::int64_t step, double t, const system::TorusState& x) override;
  double energy = 0.0;
  double p1 = 0.0;

 private:
  CardanInvariants invariants_;
  CardanInvariants::Values first_{};
  bool started_ = false;
};

/// The kit's checks of a T³ scheme (top of this file), appended to report.
void cardan_checks(const integrators::SchemeInfo& scheme, const Options& options, Report& report);

}  // namespace lgi::experiments::verification

#pragma once
// Scheme `simo-wong`: the energy–momentum scheme — implicit midpoint on the
// body momentum (and on Γ = Rᵀe3) with a Cayley attitude update.
//
// References: J. C. Simo & K. K. Wong, "Unconditionally stable algorithms for
// rigid body dynamics that exactly preserve energy and momentum", Int. J.
// Numer. Methods Eng. 31 (1991) 19–52 (the midpoint rule in the convected
// (body) description with the Cayley update, and its energy–momentum
// property); M. Austin, P. S. Krishnaprasad & L.-S. Wang, "Almost Poisson
// integration of rigid body systems", J. Comput. Phys. 107 (1993) 105–117
// (the midpoint rule for the Lie–Poisson (Π, Γ) equations of the heavy top and
// its reconstruction of R); O. Gonzalez, "Time integration and discrete
// Hamiltonian systems", J. Nonlinear Sci. 6 (1996) 449–467 (the midpoint
// discrete gradient used for potentials not linear in Γ); docs/math.md §6,
// "Energy–momentum". (Equation numbers of the papers are not quoted: the
// discrete equations below are derived and checked here, each identity by a
// test in tests/test_energy_momentum.cpp.)
//
// ── The discrete equations (body form, docs/conventions.md) ─────────────────
// Unknown W ∈ ℝ³ (the midpoint angular velocity). With ξ = hW, Ŵ v = W × v,
//   Π_mid = J W,                                    (Π_mid = (Π_n + Π_{n+1})/2)
//   Q = cay(ξ) = (I − ξ̂/2)⁻¹(I + ξ̂/2),   R_{n+1} = R_n Q,           (1)
//   Π_{n+1} − Π_n = h Π_mid × W + h τ_d,                              (2)
// i.e. the residual F(W) = 2JW − 2Π_n − h (JW) × W − h τ_d(W) = 0.
// The identity behind everything (A := ξ̂/2, Qᵀ = (I + A)⁻¹(I − A)):
//   x_{n+1} = Qᵀ x_n  ⇔  x_{n+1} − x_n = h x_mid × W,   x_mid = (x_n + x_{n+1})/2,
//   x_mid = (I + A)⁻¹ x_n.                                             (3)
// So (2) is equivalent to the update actually used once W is known,
//   Π_{n+1} = Qᵀ Π_n + h (I + A)⁻¹ τ_d,                               (2')
// and Γ_{n+1} = R_{n+1}ᵀ e3 = Qᵀ Γ_n has the midpoint Γ_mid = (I + A)⁻¹ Γ_n
// that the gravity torque must use — the midpoint consistent with the Cayley
// update, not the Γ of some "midpoint attitude".
// Discrete torque τ_d, term by term (t_mid = t_n + h/2):
//   gravity  τ_g = Γ_mid × mgχ, Γ_mid = (I + A)⁻¹ Γ_n   (V = mgχ·Γ is linear in Γ);
//   spring   τ_s = τ_m + σ ξ,  τ_m = −k log(R_restᵀ R_m),  R_m = R_n cay(η),
//            η = ξ/(1 + √(1 + |ξ|²/4))  (so cay(η)² = cay(ξ): R_m is the geodesic
//            midpoint of R_n and R_{n+1}, the same point seen from either end),
//            σ = (−[V(R_{n+1}) − V(R_n)] − τ_m·ξ)/|ξ|²: Gonzalez's midpoint
//            discrete gradient, written in the Cayley coordinate ξ of the step;
//            σ is O(h) (the bracket is O(|ξ|³): midpoint rule along the
//            geodesic), so τ_s = τ(R_m) + O(h²). Where the bracket is below its
//            own rounding (16ε(V_n + V_{n+1} + |τ_m·ξ|)) σ = 0: the energy error
//            of dropping it is that rounding, and dividing noise by |ξ|² is avoided;
//   damper   τ_c = −c W  (the midpoint Ω);
//   drive    τ(t_mid).
// ── What is conserved, exactly (to round-off), and why ──────────────────────
//   |Π| and m = RΠ (free body): (2') with τ_d = 0 is Π_{n+1} = QᵀΠ_n, and
//     R_{n+1}Π_{n+1} = R_n Q Qᵀ Π_n — for ANY W, so independently of the Newton
//     tolerance.
//   Π·Γ (heavy top): (2') gives Π_{n+1}·Γ_{n+1} = Π_n·Γ_n + h ((I+A)⁻¹τ_g)·(I−A)(I+A)⁻¹Γ_n
//     = Π_n·Γ_n + h τ_g·Γ_mid (as (I+A)⁻ᵀ = (I−A)⁻¹) = Π_n·Γ_n, again for any W.
//   H = ½Π·J⁻¹Π + V: W·(Π_{n+1} − Π_n) = h W·τ_d (the gyroscopic term drops),
//     and ΔKE = Π_mid·J⁻¹ΔΠ = W·ΔΠ. Gravity: mgχ·ΔΓ = h mgχ·(Γ_mid × W) = −h W·τ_g.
//     Spring: τ_s·ξ = −ΔV by construction of σ. Damper: ΔH = −h c |W|² ≤ 0, so the
//     energy of a damped spring decays monotonically. This needs W converged:
//     the error is ~ the Newton residual times |W| per step.
// Symmetric: (R_{n+1}, Π_{n+1}, −h) gives the same W, cay(−ξ) = Qᵀ, the same Γ_mid,
// R_m (cay(η)² = cay(ξ)) and σ; the midpoint time is shared. Order 2 (symmetric
// and consistent). Not symplectic.
// Scene support: any (gravity, springs with dampers, harmonic drives; the
// static_assert below lists what the discrete torque knows).
//
// ── The solve ────────────────────────────────────────────────────────────────
// Newton on F(W) = 0 (3 unknowns) with the analytic Jacobian
//   ∂F/∂W = 2J + h (Ŵ J − (JW)^) − h ∂τ_d/∂W,
//   gravity: −h ∂τ_g/∂W = (h²/2) (mgχ)^ (I + A)⁻¹ Γ̂_mid,
//   damper:  −h ∂τ_c/∂W = h c I,
//   spring:  ∂τ_s/∂ξ = −k ∂δ_m/∂ξ + ξ ∂σ/∂ξ + σ I  (∂/∂W = h ∂/∂ξ), with
//            ∂δ_m/∂ξ = dexp⁻¹_body(δ_m) dcay_body(η) [I/(1+r) − ξξᵀ/(4r(1+r)²)], r = √(1+|ξ|²/4),
//            ∂δ_{n+1}/∂ξ = dexp⁻¹_body(δ_{n+1}) dcay_body(ξ),  δ = log(R_restᵀ R),
//            ∂σ/∂ξ = (−k δ_{n+1}ᵀ ∂δ_{n+1}/∂ξ + k ξᵀ ∂δ_m/∂ξ + k δ_mᵀ − 2σ ξᵀ)/|ξ|².
// Predictor: W⁰ = J⁻¹(Π_n + (h/2) Π̇(R_n, Π_n, t_n)) (an O(h²) start).
// Converged when |F| ≤ 4ε·(2|Π_n| + 2|JW| + h|JW||W| + h Σ|τ terms|) + h·δσ|ξ|
// — a few ulps of the terms of F, plus, with a spring, the rounding of the
// discrete-gradient term hσξ (σ = bracket/|ξ|² amplifies the bracket's
// rounding 16ε(V_n + V_{n+1} + |τ_m·ξ|) by 1/|ξ|) — or, where rounding keeps |F|
// just above that, when the last Newton update moved W by at most 16 ulps
// (16ε|W|) and |F| is within 64× the bound: further iterations cannot improve W.
// (The bracket's rounding changes the energy by that rounding only, since
// τ_s·ξ = τ_m·ξ + bracket whatever σ's relative error.) The step is reported not converged
// (StepStatus::converged = false, with iterations and relative residual) if
// Newton fails within max_iterations, produces non-finite values, or if the
// converged step rotates by h|W| ≥ max_step_rotation (π): the Cayley update
// rotates by 2 atan(h|W|/2) < π and would silently alias such a step. (The
// stepper loop reports any of these as "implicit solve did not converge"; for
// the rotation guard the residual shown is the small, converged one.
// RunConfig::retry_halving, where used, retries such a step as halves.)
// No allocation: fixed-size Eigen types, a 3×3 LU with partial pivoting.
#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>

#include "integrators/core/scheme_interface.hpp"

namespace lgi::integrators {

class SimoWong {
 public:
  static constexpr SchemeFacts facts{
      .order = 2,
      .properties = {.symmetric = true, .conserves_energy = true, .conserves_momentum_norm = true,
                     .conserves_spatial_momentum = true, .conserves_vertical_momentum = true, .implicit = true},
      .reference = "Simo & Wong, Int. J. Numer. Methods Eng. 31 (1991) 19-52; Austin, Krishnaprasad & Wang, "
                   "J. Comput. Phys. 107 (1993) 105-117; discrete gradient: Gonzalez, J. Nonlinear Sci. 6 (1996) "
                   "449-467"};
  static constexpr int max_iterations = 25;
  /// Steps rotating by h|W| ≥ this are refused (converged = false); see the header.
  double max_step_rotation = std::numbers::pi;

  template <class Model>
  StepStatus step(const Model& model, State& s, double t, double h, WorkCounters& work) const {
    static_assert(Model::discrete_gradient,
                  "simo-wong needs a discrete torque from every torque term (DiscreteGradientTerm)");
    constexpr double eps = std::numeric_limits<double>::epsilon();
    const double t_mid = t + 0.5 * h;

    Start<Model> start;
    start.R = &s.R;
    start.Pi = s.Pi;
    start.terms = std::apply([&](const auto&... term) { return std::tuple{term.discrete_start(s.R)...}; }, model.terms);

    const Vec3 omega_n = model.omega(s.Pi);
    Vec3 W = model.omega(s.Pi + (0.5 * h) * model.momentum_rate(s.R, s.Pi, omega_n, t));
    Eval e;
    evaluate(model, start, W, h, t_mid, e);
    std::int64_t evaluations = 2;

    StepStatus status;
    status.converged = false;
    bool small_update = false;
    for (;;) {
      const double bound = 4.0 * eps * e.scale + e.noise;
      const double res = e.F.norm();
      status.residual = e.scale > 0.0 ? res / e.scale : res;
      if (!std::isfinite(res)) break;
      if (res <= bound || (small_update && res <= 64.0 * bound)) {
        status.converged = true;
        break;
      }
      if (status.iterations == max_iterations) break;
      const Vec3 delta = e.jacobian.partialPivLu().solve(e.F);
      W -= delta;
      ++status.iterations;
      small_update = delta.norm() <= 16.0 * eps * W.norm();
      evaluate(model, start, W, h, t_mid, e);
      ++evaluations;
    }
    work.rhs_evaluations += evaluations;
    if (status.converged && !(std::abs(h) * W.norm() < max_step_rotation)) {
      status.converged = false;
      status.reason = "step refused: the midpoint rotation h|W| reaches pi, beyond the Cayley update; reduce --dt";
    }
    if (!status.converged) return status;

    // (1) and (2'): R_{n+1} = R_n Q, Π_{n+1} = QᵀΠ_n + h (I + A)⁻¹ τ_d.
    s.R = e.R1;  // R_n Q, already formed
    s.Pi = e.Q.transpose() * start.Pi + h * (e.Ainv * e.tau);
    return status;
  }

 private:
  template <class Model>
  struct Start;
  template <class... Terms>
  struct Start<system::RigidBody<Terms...>> {
    const Mat3* R = nullptr;
    Vec3 Pi = Vec3::Zero();
    std::tuple<typename Terms::DiscreteStart...> terms;  // what each term keeps from R_n
  };
  struct Eval {
    Mat3 Q;         // cay(hW)
    Mat3 Ainv;      // (I + ξ̂/2)⁻¹
    Mat3 R1;        // R_n Q
    Vec3 tau;       // τ_d
    Vec3 F;         // residual
    Mat3 jacobian;  // ∂F/∂W
    double scale = 0.0;  // Σ of the magnitudes of the terms of F
    double noise = 0.0;  // rounding a term's τ_d carries (a spring's discrete gradient)
  };

  template <class Model>
  static void evaluate(const Model& model, const Start<Model>& st, const Vec3& W, double h, double t_mid, Eval& e) {
    const Mat3& J = model.inertia.J;
    system::CayleyStep step;
    step.R = st.R;
    step.xi = h * W;
    step.W = W;
    step.h = h;
    step.t_mid = t_mid;
    step.theta2 = step.xi.squaredNorm();
    const Mat3 X = lie::hat(step.xi);
    const Mat3 X2 = X * X;
    e.Q = Mat3::Identity() + (4.0 / (4.0 + step.theta2)) * (X + 0.5 * X2);
    e.Ainv = (Mat3::Identity() - 0.5 * X + 0.25 * (step.xi * step.xi.transpose())) / (1.0 + 0.25 * step.theta2);
    e.R1 = *st.R * e.Q;
    step.Ainv = e.Ainv;
    step.R1 = e.R1;
    const Vec3 pi_mid = J * W;
    e.F = 2.0 * (pi_mid - st.Pi) - h * pi_mid.cross(W);
    system::DiscreteTorque d;  // the terms add τ_d, its magnitude and their part of ∂F/∂W
    d.jacobian = 2.0 * J + h * (lie::hat(W) * J - lie::hat(pi_mid));
    std::apply(
        [&](const auto&... term) {
          std::apply([&](const auto&... start) { (term.add_discrete_torque(start, step, d), ...); }, st.terms);
        },
        model.terms);
    e.tau = d.tau;
    e.jacobian = d.jacobian;
    e.noise = d.noise;
    e.F -= h * e.tau;
    e.scale = 2.0 * (st.Pi.norm() + pi_mid.norm()) + std::abs(h) * (pi_mid.norm() * W.norm() + d.magnitude);
  }
};

}  // namespace lgi::integrators

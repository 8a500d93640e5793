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
#include <type_traits>

#include "integrators/scheme_interface.hpp"

namespace lgi::integrators {

namespace detail {
template <class T>
inline constexpr bool em_known_term = std::is_same_v<T, system::GravityTerm> ||
                                      std::is_same_v<T, system::SpringTerm> ||
                                      std::is_same_v<T, system::HarmonicDriveTerm>;
template <class M>
struct em_supported : std::false_type {};
template <class... Ts>
struct em_supported<system::RigidBody<Ts...>> : std::bool_constant<(em_known_term<Ts> && ... && true)> {};
}  // namespace detail

class SimoWong {
 public:
  static constexpr int max_iterations = 25;
  /// Steps rotating by h|W| ≥ this are refused (converged = false); see the header.
  double max_step_rotation = std::numbers::pi;

  template <class Model>
  StepStatus step(const Model& model, State& s, double t, double h, WorkCounters& work) const {
    static_assert(detail::em_supported<Model>::value,
                  "simo-wong has discrete torques for gravity, springs (with dampers) and harmonic drives only");
    constexpr double eps = std::numeric_limits<double>::epsilon();
    const double t_mid = t + 0.5 * h;

    Start start;
    start.R = &s.R;
    start.Pi = s.Pi;
    if constexpr (Model::template has_term<system::GravityTerm>) start.gamma = s.R.row(2).transpose();
    if constexpr (Model::template has_term<system::SpringTerm>)
      start.V = model.template term<system::SpringTerm>().potential(s.R);

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
    if constexpr (Model::template has_term<system::SpringTerm>) s.R = e.R1;  // R_n Q, already formed
    else s.R = s.R * e.Q;
    s.Pi = e.Q.transpose() * start.Pi + h * (e.Ainv * e.tau);
    return status;
  }

 private:
  struct Start {
    const Mat3* R = nullptr;
    Vec3 Pi = Vec3::Zero();
    Vec3 gamma = Vec3::Zero();  // Γ_n (gravity)
    double V = 0.0;             // V_spring(R_n)
  };
  struct Eval {
    Mat3 Q;         // cay(hW)
    Mat3 Ainv;      // (I + ξ̂/2)⁻¹
    Mat3 R1;        // R_n Q (formed only with a spring)
    Vec3 tau;       // τ_d
    Vec3 F;         // residual
    Mat3 jacobian;  // ∂F/∂W
    double scale = 0.0;  // Σ of the magnitudes of the terms of F
    double noise = 0.0;  // rounding of h σ ξ (spring): h·(rounding of σ|ξ|²)/|ξ|
  };

  template <class Model>
  static void evaluate(const Model& model, const Start& st, const Vec3& W, double h, double t_mid, Eval& e) {
    const Mat3& J = model.inertia.J;
    const Vec3 xi = h * W;
    const double theta2 = xi.squaredNorm();
    const Mat3 X = lie::hat(xi);
    const Mat3 X2 = X * X;
    e.Q = Mat3::Identity() + (4.0 / (4.0 + theta2)) * (X + 0.5 * X2);
    e.Ainv = (Mat3::Identity() - 0.5 * X + 0.25 * (xi * xi.transpose())) / (1.0 + 0.25 * theta2);
    const Vec3 pi_mid = J * W;
    e.F = 2.0 * (pi_mid - st.Pi) - h * pi_mid.cross(W);
    e.jacobian = 2.0 * J + h * (lie::hat(W) * J - lie::hat(pi_mid));
    e.tau.setZero();
    double tau_mag = 0.0;  // Σ |contributions to τ_d| (they may cancel in τ_d)
    e.noise = 0.0;
    if constexpr (Model::template has_term<system::GravityTerm>) {
      const Vec3& c = model.template term<system::GravityTerm>().mg_chi;
      const Vec3 gamma_mid = e.Ainv * st.gamma;
      e.tau += gamma_mid.cross(c);
      tau_mag += gamma_mid.norm() * c.norm();
      e.jacobian += (0.5 * h * h) * (lie::hat(c) * e.Ainv * lie::hat(gamma_mid));
    }
    if constexpr (Model::template has_term<system::SpringTerm>) {
      const auto& spring = model.template term<system::SpringTerm>();
      const double k = spring.stiffness;
      e.R1 = *st.R * e.Q;
      const Vec3 delta1 = spring.deflection(e.R1);
      const double V1 = 0.5 * k * delta1.squaredNorm();  // = spring.potential(R1), bit for bit
      const double r = std::sqrt(1.0 + 0.25 * theta2);
      const Vec3 eta = xi / (1.0 + r);
      const Vec3 delta_m = spring.deflection(Mat3(*st.R * lie::cay(eta)));
      const double power = k * delta_m.dot(xi);  // −τ_m·ξ
      const double num = -(V1 - st.V) + power;
      const double noise = 16.0 * std::numeric_limits<double>::epsilon() * (st.V + V1 + std::abs(power));
      const double sigma = theta2 > 0.0 && std::abs(num) > noise ? num / theta2 : 0.0;
      e.tau += -k * delta_m + sigma * xi;
      tau_mag += k * delta_m.norm() + std::abs(sigma) * std::sqrt(theta2);
      if (sigma != 0.0) e.noise = std::abs(h) * noise / std::sqrt(theta2);
      // ∂τ_s/∂ξ
      const Mat3 E_eta = Mat3::Identity() / (1.0 + r) - (xi * xi.transpose()) / (4.0 * r * (1.0 + r) * (1.0 + r));
      const Mat3 Dm = lie::dexpinv_body_matrix(delta_m) * lie::dcay_body(eta) * E_eta;
      Mat3 dtau = -k * Dm;
      if (sigma != 0.0) {
        const Mat3 D1 = lie::dexpinv_body_matrix(delta1) * lie::dcay_body(xi);
        const Eigen::RowVector3d dnum =
            -k * delta1.transpose() * D1 + k * xi.transpose() * Dm + k * delta_m.transpose();
        const Eigen::RowVector3d dsigma = (dnum - 2.0 * sigma * xi.transpose()) / theta2;
        dtau += xi * dsigma + sigma * Mat3::Identity();
      }
      e.jacobian -= (h * h) * dtau;
      if (spring.damping != 0.0) {
        e.tau -= spring.damping * W;
        tau_mag += spring.damping * W.norm();
        e.jacobian += (h * spring.damping) * Mat3::Identity();
      }
    }
    if constexpr (Model::template has_term<system::HarmonicDriveTerm>) {
      const Vec3 drive = model.template term<system::HarmonicDriveTerm>().torque(*st.R, st.Pi, W, t_mid);
      e.tau += drive;
      tau_mag += drive.norm();
    }
    e.F -= h * e.tau;
    e.scale = 2.0 * (st.Pi.norm() + pi_mid.norm()) + std::abs(h) * (pi_mid.norm() * W.norm() + tau_mag);
  }
};

}  // namespace lgi::integrators

#pragma once
// What a scheme type states about itself, as static constexpr data next to
// its formulas: order, how the loop drives it, what it conserves, which
// scenes it runs on and where it comes from. The registry reads these facts
// (registry_support.hpp, add_scheme) and retypes none of them; the generic
// tests check every claim (tests/test_stated_orders.cpp,
// tests/test_scheme_properties.cpp).
#include <concepts>
#include <type_traits>

namespace lgi::integrators {

struct SchemeProperties {
  bool symplectic = false;
  bool symmetric = false;                    // Φ₋ₕ ∘ Φₕ = id (tested to round-off)
  bool conserves_energy = false;             // exactly, to round-off
  bool conserves_momentum_norm = false;      // |Π| for a free body
  bool conserves_spatial_momentum = false;   // m = RΠ for a free body
  bool conserves_vertical_momentum = false;  // Π·Γ for a heavy top
  bool implicit = false;
  bool adaptive = false;
  /// An interpolant inside each step: output times are interpolated, not landed on, and event
  /// crossings are located on it (stepper_loop.hpp). Set by the registry from the scheme's type.
  bool dense_output = false;
  bool baseline = false;                     // a Boost.Odeint baseline in coordinates, not a Lie-group scheme
  bool euler_angle_chart = false;            // integrates Euler ZXZ angles: /particles/body/euler_zxz is written
};

/// Which scenes a scheme can run on; others are refused with exit 1.
enum class SceneSupport {
  any,
  free_body_only,     // needs the free body (the exact flow, DMV without splitting)
  conservative_only,  // torques from a potential only: no damping, no drive
  cardan_only,        // the Cardan top on T³ (schemes/torus_*.hpp, docs/cardan.md): never an SO(3) scene
};

/// The SIMD lane kernel whose step is the scheme's, bit for bit (integrators/ensemble/,
/// docs/ensemble.md): `lgi sweep` steps such a scheme's trajectories several at a time in
/// lanes. The ensemble looks a scheme's kernel up here, through the registry, and has no
/// table of scheme names; the registry builds the lane run from the scheme's own type.
enum class LaneKernel {
  none,
  rkmk4,         // ensemble/rkmk_kernel.hpp on the classical RK4 tableau in exp coordinates; scenes without a spring
  dmv_diagonal,  // ensemble/dmv_kernel.hpp: a DMV-family step on a free body with diagonal J, the scheme's
                 // own step behind each lane for the steps the kernel leaves (ensemble/lane_fallback.hpp)
};

struct SchemeFacts {
  int order = 0;              // 0: not applicable (exact)
  int order_with_torque = 0;  // order on scenes with torques where it differs (Strang splitting); 0: the same
  SchemeProperties properties{};
  SceneSupport support = SceneSupport::any;
  const char* reference = "";  // the method's papers
  const char* tableau = "";    // the coefficients' source, where they come from a table
  LaneKernel lane_kernel = LaneKernel::none;  // the ensemble's kernel of this step, if any
};

/// A scheme type that carries its facts.
template <class Scheme>
concept SchemeWithFacts = requires {
  requires std::same_as<std::remove_cvref_t<decltype(Scheme::facts)>, SchemeFacts>;
};

/// The Munthe-Kaas construction shared by the explicit and implicit RKMK schemes.
inline constexpr const char* munthe_kaas_reference =
    "Munthe-Kaas, Appl. Numer. Math. 29 (1999) 115-127; Iserles et al., Acta Numerica 9 (2000) 5.3";

}  // namespace lgi::integrators

#pragma once
// Relative equilibria of the heavy top (Staude's permanent rotations) and
// their stability: docs/atlas.md §2–§3 (formulas and sources).
//
// A permanent rotation has Ω = ωΓ constant, Π = ωJΓ, and
//   (ω²J + μI)Γ = mgχ,  |Γ| = 1,
// i.e. Γ × (mgχ − ω²JΓ) = 0. In the principal frame (J = diag A) and with
// ν = μ/ω² the solutions are, away from the poles ν = −A_i,
//   Γ = v/|v|, v_i = mgχ_i/(A_i + ν),  ω² = |v|,
// one branch per interval between poles and per sign of ω (the regular
// branches). Where χ_i = 0, ν = −A_i exactly gives a further family with
// Γ_i free (the degenerate branches: the Lagrange top's carrousels, the
// Euler top's principal-axis rotations). Along each branch ℓ = ωΓ·JΓ and
// h = ½ω²Γ·JΓ + mgχ·Γ.
//
// Stability after Grammel: the 6×6 linearisation M of the Euler–Poisson
// field in (Π, Γ) has det(λ − M) = λ²(λ⁴ + g1λ² + g2), g1 = −½ tr M²,
// g2 = (tr M²)²/8 − tr M⁴/4; the class follows from g1, g2 (docs/atlas.md §3).
// Nonlinear stability (energy–Casimir): Γ is a strict minimum of the amended
// potential U_ℓ(γ) = ℓ²/(2γ·Jγ) + mgχ·γ on the sphere.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "integrators/system/inertia.hpp"

namespace lgi::experiments {

using lie::Mat3;
using lie::Vec3;

/// A heavy top: J about the fixed point and mgχ (the weight's moment arm times m g).
struct HeavyTopBody {
  Mat3 J = Mat3::Identity();
  Vec3 weight = Vec3::Zero();  // m g χ
};

enum class EquilibriumStability { stable = 0, singly_unstable = 1, doubly_unstable = 2, complex_unstable = 3 };
const char* stability_name(EquilibriumStability s);

struct RelativeEquilibrium {
  double omega = 0.0;
  Vec3 gamma = Vec3::UnitZ();
  Vec3 angular_momentum = Vec3::Zero();  // Π = ωJΓ
  double l = 0.0, h = 0.0;
  int branch = 0;
  double g1 = 0.0, g2 = 0.0;
  EquilibriumStability stability = EquilibriumStability::stable;
  bool nonlinearly_stable = false;
  bool fold = false;       // a turning point of ℓ along its branch (a cusp of the (ℓ, h) diagram)
  bool class_change = false;  // where Grammel's class changes along its branch (located by bisection)
  double residual = 0.0;   // |ω²JΓ×Γ + Γ×mgχ| (the equilibrium equations)
};

/// How each branch is made (for the listing in EQUILIBRIA.md and lgi's output).
struct EquilibriumBranch {
  int id = 0;
  std::string kind;   // "regular (nu in (a, b))", "principal axis 3", ...
  std::string label;  // its asymptotic ends: "hanging - +e1", "+e3 - upright", "+e2" (principal axes)
};

struct EquilibriumSet {
  std::vector<RelativeEquilibrium> rows;
  std::vector<EquilibriumBranch> branches;
};

/// Every relative equilibrium at ℓ = l, each polished to round-off by Newton's
/// method on the full equations, sorted by h (then branch).
EquilibriumSet equilibria_at(const HeavyTopBody& body, double l);

/// Every branch sampled with `samples` points, every fold of ℓ along it
/// located (fold = true, golden section) and every change of Grammel's class
/// between neighbouring samples located (class_change = true, bisection to
/// round-off in the branch parameter; the row has the class of the far side),
/// in branch order and along each branch. `branch_done`, if given, is called
/// after each branch with the branches done and their number, and with the same
/// count every 2^16 samples within a branch; false stops there (the set is then
/// incomplete: a signal, the caller writes nothing).
EquilibriumSet equilibrium_branches(const HeavyTopBody& body, int samples,
                                    const std::function<bool(std::size_t, std::size_t)>& branch_done = {});

/// Grammel's coefficients and class, and the energy–Casimir test, of an
/// equilibrium (fills g1, g2, stability, nonlinearly_stable, residual).
void classify(const HeavyTopBody& body, RelativeEquilibrium& e);

}  // namespace lgi::experiments

#pragma once
// Random points of a heavy top's level set {H = h, Π·Γ = l, |Γ| = 1}, for
// the sweep engine's [level_set] (experiments/SWEEPS.md, "Level set"), and so
// for lgi poincare and lgi chaos-map. The density is the Liouville measure
// of the level set (docs/atlas.md §6 derives it) or, to reproduce runs made
// before it was chosen, Γ uniform on the sphere.
#include "experiments/analysis/seeded_random.hpp"
#include "experiments/io/sweep_spec.hpp"
#include "integrators/system/scene.hpp"
#include "lie/so3.hpp"

namespace lgi::experiments {

/// The energy of a top (gravity alone, or no torque) on {Π·Γ = l}:
/// H ≥ V(γ) + l²/(2 γᵀJγ), with equality at Π = l Jγ/(γᵀJγ) (a Lagrange
/// multiplier: ∇(½ΠᵀJ⁻¹Π) = λγ).
struct LevelSetBody {
  lie::Mat3 J, J_inv;
  lie::Vec3 weight = lie::Vec3::Zero();  // m g χ: V(γ) = m g χ·γ
  double j_min = 0.0;                    // the least principal moment: min over |γ| = 1 of γᵀJγ
  double lowest_energy(const lie::Vec3& gamma, double l) const {
    return weight.dot(gamma) + l * l / (2.0 * gamma.dot(J * gamma));
  }
};

/// The body of a scene with gravity alone or no torque.
LevelSetBody level_set_body(const system::Scene& scene);

/// The least of V(γ) + l²/(2γᵀJγ) over 20000 directions of a Fibonacci
/// lattice on the sphere (an upper bound of the minimum, within ~1e-3 relative).
double sampled_minimum(const LevelSetBody& b, double l);

/// The density of Γ on the sphere under the Liouville measure of the level
/// set, up to a constant: (γᵀJγ)^(−1/2) where V(γ) + l²/(2γᵀJγ) < h, else 0
/// (docs/atlas.md §6).
double liouville_gamma_density(const LevelSetBody& b, double h, double l, const lie::Vec3& gamma);

/// One point (γ, Π) of the level set from the draws of `rng`; false if 10⁶
/// directions of γ did not reach it. The uniform measure takes exactly the
/// draws of lgi's earlier level-set draw, so its points are those bit for bit.
bool draw_level_point(const LevelSetBody& b, double h, double l, LevelMeasure measure, CounterRng& rng,
                      lie::Vec3& gamma, lie::Vec3& Pi);

}  // namespace lgi::experiments

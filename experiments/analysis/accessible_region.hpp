#pragma once
// The accessible region of a heavy top on the Poisson sphere and the topology
// of its energy surfaces (docs/atlas.md §1 and §8; experiments/REGION.md).
//
// At fixed ℓ the amended potential U_ℓ(γ) = ℓ²/(2γ·Jγ) + m g χ·γ bounds the
// energy from below; the motion at energy h stays in P = {γ ∈ S² : U_ℓ ≤ h}.
// Over a point of the interior of P the energy surface has a circle (the
// ellipse of the remaining kinetic energy), over its boundary a point; so a
// component of P with b boundary circles carries a component of the energy
// surface that is RP³ (b = 0: P = S²), S³ (b = 1: a disc), S¹×S² (b = 2: an
// annulus) or the connected sum of b − 1 copies of S¹×S² (A. V. Bolsinov,
// H. R. Dullin and A. Wittek, J. Phys. A 29 (1996) 4977, Theorem 1).
//
// P is read off a triangulation of the sphere (the (θ, φ) grid below): the
// sub-complex of the vertices with U_ℓ ≤ h and the edges and triangles whose
// vertices all are in it. Its components are those of P and, since P is a
// planar domain, b = 2 − χ for each, with χ = V − E + F the Euler
// characteristic of the component. Morse theory checks the grid: a sublevel
// set has the homotopy type of a cell complex with one cell of dimension λ
// per critical point of index λ below h (J. Milnor, Morse Theory, Princeton
// 1963, Theorem 3.5), so χ = Σ (−1)^index over them, and the critical
// points of U_ℓ are exactly the relative equilibria at ℓ (equilibria_at). A
// component whose two counts differ is not resolved by the grid, unless it
// holds a degenerate critical point (at a bifurcation of relative equilibria,
// e.g. the Kovalevskaya top's Γ = e1 at ℓ̃ = 2, docs/atlas.md §8): U_ℓ is not
// a Morse function there, the count does not apply, and the grid alone decides.
#include <optional>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "experiments/analysis/relative_equilibria.hpp"
#include "integrators/system/scene.hpp"

namespace lgi::experiments {

/// J and m g χ of a scene's heavy top; InputError naming the scene and `command`
/// unless it is a heavy top (gravity and no other torque term) or a free body.
HeavyTopBody heavy_top_of(const system::Scene& scene, const std::string& command);

/// U_ℓ(γ) = ℓ²/(2γ·Jγ) + m g χ·γ.
double amended_potential(const HeavyTopBody& body, double l, const Vec3& gamma);

/// A critical point of U_ℓ on the sphere: a relative equilibrium at ℓ.
struct CriticalPoint {
  Vec3 gamma = Vec3::UnitZ();
  double value = 0.0;   // U_ℓ(Γ) = h of the equilibrium
  int index = 0;        // Morse index: 0 minimum, 1 saddle, 2 maximum (of the non-degenerate direction on a circle)
  bool circle = false;  // degenerate: on a circle of critical points (a symmetric body; Morse–Bott)
  bool degenerate = false;  // isolated and degenerate (a bifurcation of relative equilibria at this ℓ): not Morse
  double omega = 0.0;
  int branch = 0;
  EquilibriumStability stability = EquilibriumStability::stable;
  bool nonlinearly_stable = false;
};

/// The critical points of U_ℓ; `constant` when U_ℓ is constant (the free body at ℓ = 0).
struct CriticalSet {
  std::vector<CriticalPoint> points;
  bool constant = false;
};
CriticalSet critical_points(const HeavyTopBody& body, double l);

/// U_ℓ on the (θ, φ) grid of the body axes: θ_i = π i/n (i = 0..n), φ_j = π j/n
/// (j = 0..2n−1), γ = (sinθ cosφ, sinθ sinφ, cosθ). The rows i = 0 and n are the
/// poles (one vertex each in the triangulation).
struct SphereGrid {
  int n = 0;
  std::vector<double> U;  // (n + 1) × 2n, row-major
  int meridians() const { return 2 * n; }
  double theta(int i) const;
  double phi(int j) const;
  Vec3 direction(int i, int j) const;
  double at(int i, int j) const { return U[static_cast<std::size_t>(i) * static_cast<std::size_t>(2 * n) + static_cast<std::size_t>(j)]; }
};
/// `keep_going`, if given, is called before each ring; false stops: the grid is then empty (n = 0).
SphereGrid potential_grid(const HeavyTopBody& body, double l, int n, const std::function<bool()>& keep_going = {});

/// "RP3" (b = 0), "S3" (b = 1), "S1xS2" (b = 2), "#k(S1xS2)" (b = k + 1 ≥ 3).
std::string component_topology(int boundaries);
/// The energy surface from its components' names: "empty", "S3", "2S3", "S3 + S1xS2", "2(S1xS2)", "RP3", ...
std::string energy_surface_topology(std::vector<std::string> component_names);

/// One component of P = {U_ℓ ≤ h} (ids in the order of their lowest grid value).
struct RegionComponent {
  int id = 0;
  int euler = 0;        // χ of the grid's sub-complex
  int boundaries = 0;   // 2 − χ
  std::string topology;
  double area = 0.0;    // fraction of the sphere (grid vertices weighted by their area)
  double u_min = 0.0;   // the lowest grid value in it
  int minima = 0, saddles = 0, maxima = 0, circles = 0;  // critical points below h in it
  int euler_morse = 0;  // Σ (−1)^index over them (circles count 0)
  int degenerate = 0;   // degenerate isolated critical points below h in it: no Morse check there
};

struct Region {
  std::vector<std::int64_t> label;  // per grid point ((n + 1) × 2n), −1 outside P
  std::vector<RegionComponent> components;
  std::string topology;  // of the energy surface
  bool resolved = true;  // the grid's χ equals the Morse count in every component without a degenerate point
  bool degenerate = false;  // a degenerate critical point below h: that component's topology is the grid's alone
};
Region accessible_region(const SphereGrid& grid, const CriticalSet& critical, double h);
/// The same, polling `keep_going` every 2^20 simplices and once per ring; false stops: nullopt.
std::optional<Region> accessible_region(const SphereGrid& grid, const CriticalSet& critical, double h,
                                        const std::function<bool()>& keep_going);

/// The energy surface at each of `energies` (any order) at one ℓ: the
/// sub-complexes built incrementally (one sort of the triangulation).
struct RegionSummary {
  std::string topology;
  int components = 0;
  int euler = 0, euler_morse = 0;  // totals over the components
  bool resolved = true;
  bool degenerate = false;  // as Region::degenerate
};
/// `keep_going`, if given, is called with the number of energies done after each
/// energy and, with that number, every 2^20 simplices of the triangulation, its sort
/// and the sweep (well under 0.1 s apart even at --grid 2000: a row of `lgi region
/// --cells` reads the stop flag within itself); false stops the work and the result
/// is then empty.
std::vector<RegionSummary> region_summaries(const SphereGrid& grid, const CriticalSet& critical,
                                            const std::vector<double>& energies,
                                            const std::function<bool(std::size_t)>& keep_going = {});

}  // namespace lgi::experiments

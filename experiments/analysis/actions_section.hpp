#pragma once
// The Poincaré section of a numerical torus and the first estimate of the
// rotation number of its return map (docs/actions.md §3, steps 1–2).
//
// Section: F = c crossed rising, F one of the coordinates Π1, Π2, Π3, Γ1, Γ2,
// Γ3 and c inside the widest interval of F's range that holds no turning value
// of F (no value F takes where Ḟ = 0 along the pilot orbit). On such a level
// Ḟ ≠ 0 everywhere on the torus, so {F = c} cuts it transversally in closed
// curves, and the crossings rising lie on closed circles that the return map
// permutes; the old section p_θ = 0 is the set Γ̇3 = 0 itself, which on many
// Kovalevskaya tori is made of arcs ending at tangencies.
#include <Eigen/Core>
#include <array>
#include <vector>

namespace lgi::experiments {

using Point6 = Eigen::Matrix<double, 6, 1>;  // (Π, Γ)

struct SectionChoice {
  int coordinate = -1;  // 0..5: Π1, Π2, Π3, Γ1, Γ2, Γ3; −1: none found
  double level = 0.0;   // c
  double window = 0.0;  // width of the interval free of turning values, as a fraction of F's range
};

/// The coordinate and level with the widest window free of turning values, from the
/// samples (Π, Γ) of every step of a pilot run (turning values located by parabolas through
/// three samples). Coordinates whose range is below 1e-9 of their scale are constants and
/// skipped. A window narrower than `min_window` gives coordinate −1.
SectionChoice choose_section(const std::vector<Point6>& samples, double min_window);

/// The rotation number ρ ∈ [0, ½] (up to the sign, which the ordering cannot tell) of points
/// x_j = P^j(x_0) on one closed curve: the ρ whose order of the angles jρ mod 1 makes the
/// shortest closed polygon through the points (each coordinate scaled to unit spread). A grid
/// in ρ on the first 96 points, then a finer one about the best on all of them; good to about
/// 1/n² (n points), which the Fourier fit then refines (docs/actions.md §3).
double polygon_rotation_number(const std::vector<Point6>& points);

}  // namespace lgi::experiments

#pragma once
// The quantum top of a scene (docs/quantum.md, experiments/QUANTUM.md):
// Ĥ = Σ L̂ᵢ²/(2Jᵢ) + c·Γ̂ in a principal frame of J, where c·Γ is the sum of
// the scene's potentials of Γ alone:
//   [gravity]: V = m g χ·Γ (docs/conventions.md), c += m g χ;
//   [magnetic] with a vertical field B = B e3: V = −μ·RᵀB = −B μ·Γ, c −= B μ.
// Any other torque term (a spring, a drive, a horizontal field, a Cardan
// suspension) is not a potential of Γ and is refused (InputError naming it).
//
// The frame's axes are ordered so that the symmetries are plain in the
// Wigner basis (rotor_operators.hpp):
//  - a free body with two equal moments, or a top with J₁ = J₂ about the
//    axis of c, has that axis third: k is conserved;
//  - c along a principal axis: that axis third (C₂ about it is (−1)^k);
//  - otherwise a principal plane that contains c is made the 1–3 plane,
//    where one exists (c₂ = 0): Ĥ is then real (docs/quantum.md, §3).
#include <Eigen/Core>
#include <string>

#include "integrators/system/scene.hpp"

namespace lgi::experiments::quantum {

enum class TopSymmetry {
  free_asymmetric,   // j conserved; D₂ classes per j
  free_symmetric,    // j and k conserved (J₁ = J₂ in the frame; includes the spherical top)
  symmetric_heavy,   // k conserved (J₁ = J₂, c ∥ e3)
  axial_heavy,       // c ∥ e3 (J₁ ≠ J₂): C₂ about e3, classes by the parity of k
  general            // no symmetry used
};
const char* symmetry_name(TopSymmetry s);

struct QuantumTop {
  Eigen::Vector3d moments = Eigen::Vector3d::Ones();  // principal moments in the frame
  Eigen::Vector3d weight = Eigen::Vector3d::Zero();   // c, in the frame
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();  // columns: the frame's axes in scene body coordinates
  TopSymmetry symmetry = TopSymmetry::general;
  std::string potential;  // which terms made c
  bool is_free() const { return symmetry == TopSymmetry::free_asymmetric || symmetry == TopSymmetry::free_symmetric; }
  /// Ĥ is real in the Wigner basis (c₂ = 0).
  bool is_real() const { return weight(1) == 0.0; }
};

/// The quantum top of a scene; InputError (naming the file and table) for a
/// term that is not a potential of Γ.
QuantumTop quantum_top_of(const system::Scene& scene);

/// The top of principal moments J and weight c (in that frame), reframed as above.
QuantumTop quantum_top(const Eigen::Vector3d& moments, const Eigen::Vector3d& weight);

}  // namespace lgi::experiments::quantum

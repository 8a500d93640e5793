#include "experiments/analysis/quantum/quantum_top.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "experiments/errors/input_error.hpp"

namespace lgi::experiments::quantum {
namespace {

/// The proper rotation that makes body axis a the third (cyclic: det = +1).
Eigen::Matrix3d cyclic_to_third(int a) {
  Eigen::Matrix3d p = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 3; ++i) p(((a + 1 + i) % 3), i) = 1.0;  // new axis i = old axis a+1+i
  return p;
}

bool same(double a, double b) { return std::abs(a - b) <= 1e-14 * std::max(std::abs(a), std::abs(b)); }

/// The axis of c where c lies on one, else −1.
int axis_of(const Eigen::Vector3d& c) {
  int nonzero = 0, axis = -1;
  for (int i = 0; i < 3; ++i)
    if (c(i) != 0.0) ++nonzero, axis = i;
  return nonzero == 1 ? axis : -1;
}

}  // namespace

const char* symmetry_name(TopSymmetry s) {
  switch (s) {
    case TopSymmetry::free_asymmetric: return "free asymmetric rotor: j conserved, D2 classes";
    case TopSymmetry::free_symmetric: return "free symmetric rotor: j and k conserved";
    case TopSymmetry::symmetric_heavy: return "symmetric top with c on its axis: k conserved";
    case TopSymmetry::axial_heavy: return "c on a principal axis: C2 about it, classes by the parity of k";
    case TopSymmetry::general: return "no symmetry used";
  }
  return "";
}

QuantumTop quantum_top(const Eigen::Vector3d& moments, const Eigen::Vector3d& weight) {
  QuantumTop t;
  Eigen::Matrix3d p = Eigen::Matrix3d::Identity();
  const int axis = axis_of(weight);
  if (weight.isZero(0.0)) {
    for (int a = 0; a < 3; ++a)
      if (same(moments((a + 1) % 3), moments((a + 2) % 3))) {
        p = cyclic_to_third(a);
        break;
      }
  } else if (axis >= 0) {
    p = cyclic_to_third(axis);
  } else if (weight(1) != 0.0) {
    if (weight(0) == 0.0) {  // new axes (e2, −e1, e3): c₂' = −c₁ = 0
      p << 0, -1, 0, 1, 0, 0, 0, 0, 1;
    } else if (weight(2) == 0.0) {  // new axes (e2, e3, e1): c₂' = c₃ = 0
      p = cyclic_to_third(0);
    }
  }
  t.frame = p;
  t.weight = p.transpose() * weight;
  for (int i = 0; i < 3; ++i) t.moments(i) = moments.dot(p.col(i).cwiseAbs());
  const bool sym12 = same(t.moments(0), t.moments(1));
  if (weight.isZero(0.0))
    t.symmetry = sym12 ? TopSymmetry::free_symmetric : TopSymmetry::free_asymmetric;
  else if (axis >= 0)
    t.symmetry = sym12 ? TopSymmetry::symmetric_heavy : TopSymmetry::axial_heavy;
  else
    t.symmetry = TopSymmetry::general;
  return t;
}

QuantumTop quantum_top_of(const system::Scene& scene) {
  if (scene.suspension)
    throw InputError(scene.file + ": [suspension]: a Cardan top is not a rigid rotor with a potential of Gamma; "
                     "lgi quantum takes SO(3) scenes");
  if (scene.declared<system::SpringTerm>())
    throw InputError(scene.file + ": [spring]: not a potential of Gamma (it depends on the whole attitude); "
                     "lgi quantum takes gravity and a vertical magnetic field only");
  if (scene.declared<system::HarmonicDriveTerm>())
    throw InputError(scene.file + ": [drive]: a time-dependent torque has no potential; "
                     "lgi quantum takes gravity and a vertical magnetic field only");
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  std::string potential;
  if (const auto& g = scene.declared<system::GravityTerm>()) {
    c += scene.mass.value_or(0.0) * g->g * scene.center_of_mass.value_or(Eigen::Vector3d::Zero());
    potential = "gravity: m g chi.Gamma";
  }
  if (const auto& mag = scene.declared<system::MagneticDipoleTerm>()) {
    if (mag->field(0) != 0.0 || mag->field(1) != 0.0)
      throw InputError(scene.file + ": [magnetic] field: a field with a horizontal part is not a potential of "
                       "Gamma alone (m is not conserved); lgi quantum takes a vertical field [0, 0, B]");
    c -= mag->field(2) * mag->dipole_moment;
    potential += std::string(potential.empty() ? "" : " + ") + "magnetic: -B mu.Gamma";
  }
  if (potential.empty()) potential = "none (free body)";
  // The principal frame of J: kept as given where J is diagonal; else the eigenvectors, made proper.
  Eigen::Matrix3d q = Eigen::Matrix3d::Identity();
  Eigen::Vector3d moments = scene.inertia.diagonal();
  const Eigen::Matrix3d off = scene.inertia - Eigen::Matrix3d(moments.asDiagonal());
  if (!off.isZero(0.0)) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(scene.inertia);
    q = es.eigenvectors();
    if (q.determinant() < 0.0) q.col(2) = -q.col(2);
    moments = es.eigenvalues();
  }
  QuantumTop t = quantum_top(moments, q.transpose() * c);
  t.frame = q * t.frame;
  t.potential = potential;
  return t;
}

}  // namespace lgi::experiments::quantum

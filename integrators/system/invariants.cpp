#include "integrators/system/invariants.hpp"

#include <cmath>
#include <variant>

namespace lgi::system {
namespace {
bool nearly(double a, double b) { return std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b)); }
bool is_diagonal(const Mat3& J) { return J(0, 1) == 0.0 && J(0, 2) == 0.0 && J(1, 2) == 0.0; }
}  // namespace

SceneInvariants::SceneInvariants(const Scene& scene, const AnyModel& model) : model_(&model) {
  free_body_ = std::holds_alternative<FreeBody>(model);
  // The Casimir Π·Γ and the top's integrals need gravity and no other torque.
  heavy_top_ = scene.declares_only<GravityTerm>();
  // The field's Casimir Π·RᵀB, as Π·Γ for gravity (docs/conventions.md §6).
  magnetic_only_ = scene.declares_only<MagneticDipoleTerm>();
  if (magnetic_only_) field_ = scene.declared<MagneticDipoleTerm>()->field;
  const Mat3& J = scene.inertia;
  if (heavy_top_ && is_diagonal(J) && scene.center_of_mass) {
    const Vec3 chi = *scene.center_of_mass;
    lagrange_ = nearly(J(0, 0), J(1, 1)) && chi.x() == 0.0 && chi.y() == 0.0;
    kovalevskaya_ = nearly(J(0, 0), J(1, 1)) && nearly(J(0, 0), 2.0 * J(2, 2)) && chi.y() == 0.0 && chi.z() == 0.0 &&
                    chi.x() != 0.0;
    if (kovalevskaya_) kovalevskaya_c_ = *scene.mass * scene.declared<GravityTerm>()->g * chi.x() / J(2, 2);
  }
  energy_conserved_ = std::visit([](const auto& m) { return m.is_conservative(); }, model);
  if (free_body_) names_.push_back("angular_momentum_norm");
  if (heavy_top_) names_.push_back("casimir_vertical_momentum");
  if (lagrange_) names_.push_back("lagrange_spin_momentum");
  if (kovalevskaya_) names_.push_back("kovalevskaya_k");
  if (magnetic_only_) names_.push_back("casimir_field_momentum");
}

std::vector<std::string> SceneInvariants::all_names() const {
  std::vector<std::string> all;
  if (energy_conserved_) all.push_back("energy");
  for (const auto& n : names_) all.push_back(n);
  if (free_body_) all.push_back("angular_momentum_space");
  return all;
}

double SceneInvariants::energy(const State& s) const {
  return std::visit([&](const auto& m) { return m.energy(s); }, *model_);
}

Vec3 SceneInvariants::omega(const State& s) const {
  return std::visit([&](const auto& m) { return Vec3(m.omega(s.Pi)); }, *model_);
}

InvariantValues SceneInvariants::evaluate(const State& s) const {
  InvariantValues v;
  v.energy = energy(s);
  v.orthogonality_error = lie::orthogonality_error(s.R);
  std::size_t k = 0;
  if (free_body_) {
    v.space_momentum = s.R * s.Pi;
    v.scalars[k++] = s.Pi.norm();
  }
  if (heavy_top_) {
    const Vec3 Gamma = s.R.row(2).transpose();
    v.scalars[k++] = s.Pi.dot(Gamma);
    if (lagrange_) v.scalars[k++] = s.Pi.z();
    if (kovalevskaya_) {
      const Vec3 W = omega(s);
      const double c = kovalevskaya_c_;
      const double a = W.x() * W.x() - W.y() * W.y() - c * Gamma.x();
      const double b = 2.0 * W.x() * W.y() - c * Gamma.y();
      v.scalars[k++] = a * a + b * b;
    }
  }
  if (magnetic_only_) v.scalars[k++] = s.Pi.dot(s.R.transpose() * field_);
  return v;
}

std::vector<std::string> SceneInvariants::error_names() const {
  std::vector<std::string> names;
  if (energy_conserved_) names.push_back("energy");
  names.insert(names.end(), names_.begin(), names_.end());
  if (free_body_) names.push_back("angular_momentum_space");
  names.push_back("orthogonality");
  return names;
}

void SceneInvariants::errors(const InvariantValues& initial, const InvariantValues& v, std::vector<double>& out) const {
  out.resize((energy_conserved_ ? 1 : 0) + names_.size() + (free_body_ ? 1 : 0) + 1);
  std::size_t c = 0;
  if (energy_conserved_) out[c++] = relative_error(v.energy, initial.energy);
  for (std::size_t k = 0; k < names_.size(); ++k) out[c++] = relative_error(v.scalars[k], initial.scalars[k]);
  if (free_body_) {
    const double m0 = initial.space_momentum.norm();
    const double d = (v.space_momentum - initial.space_momentum).norm();
    out[c++] = m0 > 0.0 ? d / m0 : d;
  }
  out[c] = v.orthogonality_error;
}

}  // namespace lgi::system

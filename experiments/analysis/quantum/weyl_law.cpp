// Weyl's law for the quantum top (weyl_law.hpp; docs/quantum.md §8).
#include "experiments/analysis/quantum/weyl_law.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>

namespace lgi::experiments::quantum {

WeylCounting::WeylCounting(const QuantumTop& top, double hbar, int m, int nodes) {
  if (!(hbar > 0.0) || nodes < 2) throw std::invalid_argument("Weyl's law: hbar > 0 and nodes >= 2 needed");
  const double pi = std::numbers::pi, l = m * hbar;
  const Eigen::Vector3d& J = top.moments;
  const double volume_factor = std::sqrt(J(0) * J(1) * J(2));
  const int nu = nodes, nphi = 2 * nodes;
  const double du = 2.0 / nu, dphi = 2.0 * pi / nphi;
  struct Node {
    double threshold, weight;
  };
  std::vector<Node> all;
  all.reserve(static_cast<std::size_t>(nu) * static_cast<std::size_t>(nphi));
  for (int i = 0; i < nu; ++i) {
    const double u = -1.0 + (i + 0.5) * du, s = std::sqrt(1.0 - u * u);
    for (int p = 0; p < nphi; ++p) {
      const double phi = (p + 0.5) * dphi;
      const Eigen::Vector3d gamma(s * std::cos(phi), s * std::sin(phi), u);
      const double gjg = gamma.dot(J.cwiseProduct(gamma));
      // The ellipse {Π⊥ ⊥ Γ: T(ℓΓ + Π⊥) ≤ K} has area 2π K_eff √(J₁J₂J₃/ΓᵀJΓ),
      // K_eff = K − ℓ²/(2ΓᵀJΓ) (the least kinetic energy at Π·Γ = ℓ).
      all.push_back({top.weight.dot(gamma) + l * l / (2.0 * gjg), du * dphi * 2.0 * pi * volume_factor / std::sqrt(gjg)});
    }
  }
  std::sort(all.begin(), all.end(), [](const Node& a, const Node& b) { return a.threshold < b.threshold; });
  threshold_.resize(all.size());
  weight_sum_.assign(all.size() + 1, 0.0);
  weighted_sum_.assign(all.size() + 1, 0.0);
  for (std::size_t i = 0; i < all.size(); ++i) {
    threshold_[i] = all[i].threshold;
    weight_sum_[i + 1] = weight_sum_[i] + all[i].weight;
    weighted_sum_[i + 1] = weighted_sum_[i] + all[i].weight * all[i].threshold;
  }
  scale_ = 1.0 / (4.0 * pi * pi * hbar * hbar);
}

double WeylCounting::operator()(double energy) const {
  // Vol(E) = Σ_{threshold < E} w (E − threshold).
  const auto below = static_cast<std::size_t>(std::lower_bound(threshold_.begin(), threshold_.end(), energy) -
                                              threshold_.begin());
  return scale_ * (energy * weight_sum_[below] - weighted_sum_[below]);
}

double free_rotor_weyl_count(const Eigen::Vector3d& J, double hbar, int j, double energy, int nodes) {
  const double pi = std::numbers::pi, L = hbar * (j + 0.5), e = energy / (L * L);
  const double b = 1.0 / (2.0 * J(2));
  double solid_angle = 0.0;
  for (int p = 0; p < nodes; ++p) {
    const double phi = (p + 0.5) * 2.0 * pi / nodes;
    const double c = std::cos(phi), s = std::sin(phi);
    const double a = c * c / (2.0 * J(0)) + s * s / (2.0 * J(1));
    // n̂ = (√(1−u²) cos φ, √(1−u²) sin φ, u): the form is a + u²(b − a) ≤ e;
    // the length of that set of u in [−1, 1].
    double length = 0.0;
    if (b > a) {
      length = 2.0 * std::min(1.0, std::sqrt(std::max(0.0, (e - a) / (b - a))));
    } else if (b < a) {
      length = 2.0 * (1.0 - std::min(1.0, std::sqrt(std::max(0.0, (a - e) / (a - b)))));
    } else {
      length = a <= e ? 2.0 : 0.0;
    }
    solid_angle += length * 2.0 * pi / nodes;
  }
  return (j + 0.5) / (2.0 * pi) * solid_angle;
}

}  // namespace lgi::experiments::quantum

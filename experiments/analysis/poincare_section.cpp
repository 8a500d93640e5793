#include "experiments/analysis/poincare_section.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <variant>

#include "experiments/analysis/chaos_indicators.hpp"
#include "integrators/ensemble/tangent_ensemble.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/trajectory_observer.hpp"
#include "integrators/system/model.hpp"
#include "integrators/core/tangent_flow.hpp"

namespace lgi::experiments {

namespace {

Vec3 center_of_mass(const system::Scene& scene) {
  return scene.declared<system::GravityTerm>() ? scene.center_of_mass.value_or(Vec3::Zero()) : Vec3::Zero();
}

}  // namespace

Vec3 default_section_axis(const system::Scene& scene) {
  const Vec3 chi = center_of_mass(scene);
  if (chi.norm() == 0.0) return Vec3::UnitZ();
  const Mat3& J = scene.inertia;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const bool on_axis = chi(i) == 0.0 && chi(j) == 0.0;
    const bool diagonal = J(i, j) == 0.0 && J(i, k) == 0.0 && J(j, k) == 0.0;
    if (on_axis && diagonal && J(i, i) == J(j, j)) return Vec3::Unit(k);  // a Lagrange top
  }
  return chi.normalized();
}

Vec3 parse_section_axis(const std::string& text, const system::Scene& scene) {
  if (text == "e1") return Vec3::UnitX();
  if (text == "e2") return Vec3::UnitY();
  if (text == "e3") return Vec3::UnitZ();
  if (text == "com") {
    const Vec3 chi = center_of_mass(scene);
    if (chi.norm() == 0.0) throw UsageError("--axis: com: the body " + scene.file + " has no centre of mass off the fixed point");
    return chi.normalized();
  }
  std::stringstream in(text);
  Vec3 e;
  char c1 = 0, c2 = 0;
  if (!(in >> e.x() >> c1 >> e.y() >> c2 >> e.z()) || c1 != ',' || c2 != ',' || !in.eof() || !e.allFinite() ||
      e.norm() == 0.0)
    throw UsageError("--axis: \"" + text + "\": expected e1, e2, e3, com or a non-zero body vector x,y,z");
  return e.normalized();
}

void section_frame(const Vec3& e, Vec3& f1, Vec3& f2) {
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(e(i)) < std::abs(e(k))) k = i;
  f1 = (Vec3::Unit(k) - e(k) * e).normalized();
  f2 = e.cross(f1);
}

SectionPoint section_point(SectionKind kind, const Vec3& e, const Vec3& gamma, const Vec3& Pi, const Mat3& J_inv) {
  Vec3 f1, f2;
  section_frame(e, f1, f2);
  const Vec3 Omega = J_inv * Pi;
  SectionPoint p;
  double phi = std::atan2(gamma.dot(f2), gamma.dot(f1));
  if (phi < 0.0) phi += 2.0 * std::numbers::pi;
  p.phi = phi >= 2.0 * std::numbers::pi ? 0.0 : phi;
  if (kind == SectionKind::richter) {
    p.theta = std::acos(std::clamp(gamma.dot(e) / gamma.norm(), -1.0, 1.0));
    const double phi_rate = gamma.dot(e) * gamma.dot(Omega) - Omega.dot(e);  // e·(Γ × Γ̇), |Γ| = 1
    p.sheet = phi_rate < 0.0 ? -1 : 1;
  } else {
    const double n = Pi.norm();
    p.theta = n > 0.0 ? std::acos(std::clamp(Pi.dot(e) / n, -1.0, 1.0)) : 0.0;
    p.sheet = gamma.cross(Omega).dot(e) < 0.0 ? -1 : 1;
  }
  return p;
}

double minimum_energy(const HeavyTopBody& body, double l) {
  double lowest = INFINITY;
  for (const auto& e : equilibria_at(body, l).rows) lowest = std::min(lowest, e.h);
  constexpr int n = 20000;  // a Fibonacci lattice: an upper bound, in case a branch were missed
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < n; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / n, r = std::sqrt(1.0 - z * z);
    const Vec3 g(r * std::cos(golden * k), r * std::sin(golden * k), z);
    lowest = std::min(lowest, body.weight.dot(g) + l * l / (2.0 * g.dot(body.J * g)));
  }
  return lowest;
}

OrbitIndicators orbit_indicators(const system::Scene& scene, const system::State& x0, double t_end, double dt,
                                 std::uint64_t seed, std::int64_t index) {
  integrators::Vec6 v = initial_tangent(seed, index);
  const system::AnyModel model = system::make_model(scene);
  return integrators::ensemble::with_tangent_step(model, [&](auto step) {
    system::State x = x0;
    // interrupt_requested (io/trajectory_observer.hpp): Ctrl-C ends a long orbit too
    const auto r = integrators::accumulate_chaos_indicators(
        [&](double t, double h, integrators::Vec6& w) { step(x, w, t, h); }, [&] { return x.Pi.allFinite(); }, v, 0.0,
        t_end, dt, &interrupt_requested);
    return OrbitIndicators{r.lyapunov, r.megno};
  });
}

void orbit_indicators(const system::Scene& scene, std::span<const system::State> x0, double t_end, double dt,
                      std::uint64_t seed, std::span<const std::int64_t> index, std::optional<integrators::ensemble::Isa> isa,
                      std::span<OrbitIndicators> out) {
  const system::AnyModel model = system::make_model(scene);
  std::optional<integrators::ensemble::TangentEnsemble> e;
  if (isa) e = integrators::ensemble::TangentEnsemble::make(model, *isa);
  std::size_t first = 0;
  while (first < x0.size()) {
    if (!e) {
      out[first] = orbit_indicators(scene, x0[first], t_end, dt, seed, index[first]);
      ++first;
      continue;
    }
    const std::size_t n = std::min(x0.size() - first, static_cast<std::size_t>(e->lanes()));
    for (std::size_t l = 0; l < n; ++l)
      e->set_lane(static_cast<int>(l), x0[first + l], initial_tangent(seed, index[first + l]));
    integrators::ChaosIndicators r[integrators::ensemble::max_lanes];
    e->chaos_indicators(0.0, t_end, dt, &interrupt_requested, {r, n});
    for (std::size_t l = 0; l < n; ++l) out[first + l] = OrbitIndicators{r[l].lyapunov, r[l].megno};
    first += n;
  }
}

}  // namespace lgi::experiments

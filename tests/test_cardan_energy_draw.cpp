// The microcanonical draw on {H = h} of the Cardan top
// (analysis/cardan_energy_draw.hpp, docs/cardan.md §9.4): every state on the
// level, a function of (seed, index) alone, the marginal of q against a
// quadrature of ρ(q) ∝ √(det M (h − U)), and the momenta given q uniform in
// direction after whitening by M (E[y yᵀ] = I/3 for y = L⁻¹p/√(2(h − U))).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>

#include "experiments/analysis/cardan_energy_draw.hpp"

namespace test_cardan_energy_draw {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;

namespace {

/// Richter's general top in thin rings, tilted, with a heavy inner ring off
/// centre, so that U depends on all three angles.
system::CardanTop tilted_top() {
  system::CardanTop top;
  top.J = lie::Vec3(1.0, 1.5, 2.0).asDiagonal();
  top.mass = 1.0, top.g = 1.0, top.chi = lie::Vec3(0.8, 0.4, 0.3);
  top.suspension.tilt = 0.7;
  top.suspension.outer_inertia = 0.3, top.suspension.inner_inertia = lie::Vec3(0.15, 0.3, 0.15);
  top.suspension.inner_mass = 0.5, top.suspension.inner_center = lie::Vec3(0.2, 0.1, 0.0);
  return top;
}

/// ∫ f ρ / ∫ ρ on an n³ lattice of T³ (the midpoint rule, spectrally accurate for smooth periodic f ρ).
template <class F>
double quadrature_mean(const system::CardanTop& top, double h, F f, int n = 40) {
  double num = 0.0, den = 0.0;
  const double step = 2.0 * std::numbers::pi / n;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const lie::Vec3 q((i + 0.5) * step, (j + 0.5) * step, (k + 0.5) * step);
        const double surplus = h - top.potential(q);
        if (!(surplus > 0.0)) continue;
        const double rho = std::sqrt(top.mass_matrix(q).determinant() * surplus);
        num += f(q) * rho, den += rho;
      }
  return num / den;
}

}  // namespace

TEST_CASE("Cardan energy draws lie on the level, seeded per orbit", "[cardan][chaos_map]") {
  const system::CardanTop top = tilted_top();
  const double h = 0.4;
  for (std::int64_t i = 0; i < 200; ++i) {
    system::TorusState x, again;
    REQUIRE(experiments::draw_cardan_energy_point(top, h, 7, i, x));
    CHECK(std::abs(top.energy(x) - h) < 1e-12);
    REQUIRE(experiments::draw_cardan_energy_point(top, h, 7, i, again));
    CHECK(((x.q.array() == again.q.array()).all() && (x.p.array() == again.p.array()).all()));
  }
  system::TorusState a, b;
  REQUIRE(experiments::draw_cardan_energy_point(top, h, 7, 0, a));
  REQUIRE(experiments::draw_cardan_energy_point(top, h, 8, 0, b));
  CHECK(a.q != b.q);
  // Below the least potential nothing is kept (few tries, to stay fast).
  const double lowest = experiments::cardan_sampled_minimum_potential(top);
  CHECK_FALSE(experiments::draw_cardan_energy_point(top, lowest - 0.1, 7, 0, a, 10000));
  // The envelope bounds the density everywhere it is sampled.
  const double bound = experiments::cardan_energy_density_bound(top, h);
  for (int i = 0; i < 1000; ++i) {
    const lie::Vec3 q(0.01 * i, 0.037 * i, 0.071 * i);
    const double surplus = h - top.potential(q);
    if (surplus > 0.0) CHECK(std::sqrt(top.mass_matrix(q).determinant() * surplus) <= bound);
  }
}

TEST_CASE("Cardan energy draws follow the microcanonical measure", "[cardan][chaos_map]") {
  const system::CardanTop top = tilted_top();
  const double h = 0.4;
  const int n = 20000;
  const auto cos2 = [](const lie::Vec3& q) { return std::cos(q(1)); };
  const auto potential = [&](const lie::Vec3& q) { return top.potential(q); };
  double s_cos = 0.0, s_cos2 = 0.0, s_u = 0.0, s_u2 = 0.0;
  Eigen::Matrix3d yy = Eigen::Matrix3d::Zero();
  for (int i = 0; i < n; ++i) {
    system::TorusState x;
    REQUIRE(experiments::draw_cardan_energy_point(top, h, 2026, i, x));
    const double c = cos2(x.q), u = potential(x.q);
    s_cos += c, s_cos2 += c * c, s_u += u, s_u2 += u * u;
    const Eigen::LLT<Eigen::Matrix3d> llt(top.mass_matrix(x.q));
    const Eigen::Vector3d y = llt.matrixL().solve(x.p) / std::sqrt(2.0 * (h - u));
    yy += y * y.transpose();
  }
  const auto within = [n](double sum, double sum2, double expected) {
    const double mean = sum / n, sd = std::sqrt((sum2 / n - mean * mean) / n);
    INFO("mean " << mean << " expected " << expected << " standard error " << sd);
    CHECK(std::abs(mean - expected) < 4.0 * sd);
  };
  within(s_cos, s_cos2, quadrature_mean(top, h, cos2));
  within(s_u, s_u2, quadrature_mean(top, h, potential));
  // y uniform on S²: E[y yᵀ] = I/3; each entry's standard error is below 0.3/√n.
  yy /= n;
  CHECK((yy - Eigen::Matrix3d::Identity() / 3.0).cwiseAbs().maxCoeff() < 4.0 * 0.3 / std::sqrt(n));
}

}  // namespace test_cardan_energy_draw

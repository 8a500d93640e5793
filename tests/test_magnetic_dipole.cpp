// The magnetic dipole term (integrators/system/terms/magnetic_dipole.hpp),
// added through the open-term path only: its formulas, its scene table, and
// its physics through the registry's schemes.
//   - τ = μ × RᵀB and V = −μ·RᵀB, and τ is minus the derivative of V;
//   - with μ along b3 and B along e3 the magnet is a heavy top with
//     m g χ = −μ|B|: every scheme gives the same motion on both scenes;
//   - simo-wong keeps its energy and the Casimir Π·RᵀB to round-off, and
//     split-exact keeps the Casimir (the kick is ⊥ RᵀB);
//   - a [magnetic] table with a missing key is refused with one line.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "experiments/io/scene_reader.hpp"
#include "integrators/registry/registry.hpp"
#include "lie/so3.hpp"
#include "support/registered_run.hpp"
#include "support/shipped_scene.hpp"

namespace test_magnetic_dipole {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using lie::Mat3;
using lie::Vec3;

namespace {

system::Scene magnet() { return testing::shipped_scene("magnetic_top"); }

/// The same body as a heavy top: gravity with m g χ = −μ |B| along b3.
system::Scene equivalent_heavy_top(const system::Scene& magnetic) {
  system::Scene top = magnetic;
  const auto& p = *magnetic.declared<system::MagneticDipoleTerm>();
  top.declared<system::MagneticDipoleTerm>().reset();
  top.declared<system::GravityTerm>() = system::GravityTerm::Parameters{9.81};
  top.center_of_mass = -p.dipole_moment * p.field.z() / (*top.mass * 9.81);
  return top;
}

double casimir(const system::Scene& s, const system::State& x) {
  return x.Pi.dot(x.R.transpose() * s.declared<system::MagneticDipoleTerm>()->field);
}

}  // namespace

TEST_CASE("the dipole's torque is mu x R^T B and minus the derivative of V = -mu . R^T B", "[magnetic]") {
  const system::MagneticDipoleTerm term =
      system::MagneticDipoleTerm::from_scene({Vec3(0.3, -1.2, 2.0), Vec3(0.5, 0.1, -0.7)}, {});
  const Vec3 mu(0.3, -1.2, 2.0), B(0.5, 0.1, -0.7);
  for (const Vec3& psi : {Vec3(0.1, 0.2, 0.3), Vec3(-1.0, 2.0, 0.5), Vec3(2.5, -0.3, 1.1)}) {
    const Mat3 R = lie::exp_so3(psi);
    const Vec3 b = R.transpose() * B;
    const Vec3 tau = term.torque(R, Vec3::Zero(), Vec3::Zero(), 0.0);
    CHECK((tau - mu.cross(b)).norm() <= 1e-14);
    CHECK(std::abs(term.potential(R) + mu.dot(b)) <= 1e-14);
    // τ·η = −dV/dε of V(R exp(εη̂)) (central difference).
    for (int j = 0; j < 3; ++j) {
      const double eps = 1e-6;
      const Vec3 eta = Vec3::Unit(j);
      const double dV = (term.potential(R * lie::exp_so3(eps * eta)) - term.potential(R * lie::exp_so3(-eps * eta))) /
                        (2.0 * eps);
      CHECK(std::abs(tau.dot(eta) + dV) <= 1e-8);
    }
  }
}

TEST_CASE("a magnet along its axis in a field along e3 moves as the equivalent heavy top", "[magnetic]") {
  const system::Scene m = magnet();
  const system::Scene top = equivalent_heavy_top(m);
  const system::AnyModel magnetic_model = system::make_model(m);
  const system::AnyModel top_model = system::make_model(top);
  for (const char* name : {"rkmk4", "cg4a", "simo-wong", "split-exact", "lgvi", "rkmk-gauss4", "quat/rk4"}) {
    const auto& scheme = testing::registered_scheme(name);
    const system::State a = testing::final_state_ok(scheme, magnetic_model, m.initial, 0.5, 1e-3);
    const system::State b = testing::final_state_ok(scheme, top_model, top.initial, 0.5, 1e-3);
    INFO(name);
    // The two scenes differ in the rounding of μ|B| versus m g χ only.
    CHECK(lie::geodesic_distance(a.R, b.R) <= 1e-11);
    CHECK((a.Pi - b.Pi).norm() <= 1e-11 * b.Pi.norm());
  }
}

TEST_CASE("simo-wong keeps the magnet's energy and Pi . R^T B; split-exact keeps Pi . R^T B", "[magnetic]") {
  const system::Scene m = magnet();
  const system::AnyModel model = system::make_model(m);
  const double e0 = std::visit([&](const auto& md) { return md.energy(m.initial); }, model);
  const double c0 = casimir(m, m.initial);
  const system::State sw = testing::final_state_ok(testing::registered_scheme("simo-wong"), model, m.initial, 5.0, 1e-2);
  const double e1 = std::visit([&](const auto& md) { return md.energy(sw); }, model);
  CHECK(std::abs(e1 - e0) <= 1e-12 * std::abs(e0));
  CHECK(std::abs(casimir(m, sw) - c0) <= 1e-12 * std::abs(c0));
  const system::State se =
      testing::final_state_ok(testing::registered_scheme("split-exact"), model, m.initial, 5.0, 1e-2);
  CHECK(std::abs(casimir(m, se) - c0) <= 1e-12 * std::abs(c0));
  // And a non-conserving scheme does drift (so the checks above can fail).
  const system::State rk = testing::final_state_ok(testing::registered_scheme("rkmk4"), model, m.initial, 5.0, 1e-2);
  CHECK(std::abs(std::visit([&](const auto& md) { return md.energy(rk); }, model) - e0) > 1e-10 * std::abs(e0));
}

TEST_CASE("a [magnetic] table without its field is refused with one line naming the key", "[magnetic][scene]") {
  const std::string text = R"(name = "magnet"
[body]
inertia = [1.0, 1.0, 2.0]
[magnetic]
dipole_moment = [0.0, 0.0, 1.0]
)";
  try {
    experiments::parse_scene(text, "magnet.toml");
    FAIL("accepted a [magnetic] table without field");
  } catch (const experiments::InputError& e) {
    const std::string what = e.what();
    CHECK(what.find("magnet.toml") != std::string::npos);
    CHECK(what.find("[magnetic] field") != std::string::npos);
    CHECK(what.find('\n') == std::string::npos);
  }
}

}  // namespace test_magnetic_dipole

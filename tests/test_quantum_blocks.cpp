// The symmetry blocks and eigensolvers of lgi quantum
// (experiments/analysis/quantum/): a top's levels solved per block (per k for
// a Lagrange top, per parity of k where c lies on a principal axis) equal
// those of the whole matrix; Spectra's shift-and-invert Lanczos, on a real
// and on a complex Hermitian matrix (through its real 2n form), equals the
// dense solver; the scene's terms that are not potentials of Γ are refused.
#include <catch2/catch.hpp>
#include <cmath>
#include <set>

#include "experiments/analysis/quantum/lowest_levels.hpp"
#include "experiments/analysis/quantum/quantum_spectrum.hpp"
#include "experiments/io/scene_reader.hpp"
#include "support/shipped_scene.hpp"

namespace test_quantum_blocks {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi::experiments;
using namespace lgi::experiments::quantum;

namespace {

std::vector<double> energies(const QuantumTop& top, int m, int levels, bool use_symmetry = true) {
  QuantumSettings s;
  s.hbar = 0.15, s.m = m, s.jmax = 14, s.levels = levels, s.use_symmetry = use_symmetry;
  std::vector<double> e;
  for (const auto& l : quantum_spectrum(top, s).levels) e.push_back(l.energy);
  return e;
}

double max_difference(const std::vector<double>& a, const std::vector<double>& b) {
  REQUIRE(a.size() == b.size());
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

}  // namespace

TEST_CASE("quantum: levels per block equal the levels of the whole matrix", "[quantum]") {
  // Per k (Lagrange), per parity of k (c on an axis; at m = 0 also per reflection
  // class), per reflection class (c in the 1–3 plane, m = 0): the same levels as one block.
  const QuantumTop lagrange = quantum_top(Eigen::Vector3d(1.0, 1.0, 0.4), Eigen::Vector3d(0.0, 0.0, 0.7));
  const QuantumTop axial = quantum_top(Eigen::Vector3d(1.0, 1.5, 2.0), Eigen::Vector3d(0.8, 0.0, 0.0));
  const QuantumTop planar = quantum_top(Eigen::Vector3d(1.0, 1.5, 2.0), Eigen::Vector3d(0.8, 0.0, 0.3));
  REQUIRE(lagrange.symmetry == TopSymmetry::symmetric_heavy);
  REQUIRE(axial.symmetry == TopSymmetry::axial_heavy);
  CHECK(axial.weight.isApprox(Eigen::Vector3d(0.0, 0.0, 0.8)));  // c made the third axis
  REQUIRE((planar.symmetry == TopSymmetry::general && planar.is_real()));
  for (const int m : {0, 2})
    for (const QuantumTop* top : {&lagrange, &axial, &planar}) {
      INFO("m = " << m << ", " << symmetry_name(top->symmetry));
      CHECK(max_difference(energies(*top, m, 25), energies(*top, m, 25, false)) < 1e-11);
    }
  QuantumSettings s;
  s.hbar = 0.15, s.m = 0, s.jmax = 14, s.levels = 40;
  std::set<int> classes;
  for (const auto& l : quantum_spectrum(axial, s).levels) classes.insert(l.parity);
  CHECK(classes == std::set<int>{0, 1, 2, 3});
  classes.clear();
  for (const auto& l : quantum_spectrum(planar, s).levels) classes.insert(l.parity);
  CHECK(classes == std::set<int>{0, 1});
}

TEST_CASE("quantum: Spectra's Lanczos equals the dense solver, real and complex", "[quantum]") {
  const WignerBasis b = WignerBasis::up_to(1, 24);  // 624 states: above dense_limit
  REQUIRE(b.size() > dense_limit);
  const RotorOperators ops = rotor_operators(b, 0.1);
  const Eigen::Vector3d J(1.0, 1.5, 2.0);
  for (const Eigen::Vector3d& c : {Eigen::Vector3d(0.8, 0.0, 0.3), Eigen::Vector3d(0.8, 0.4, 0.3)}) {
    const ComplexSparse h = kinetic_energy(ops, J) + potential_energy(ops, c);
    const LowestLevels lanczos = lowest_levels(h, 30, -c.norm());
    CHECK(lanczos.method.find("spectra") != std::string::npos);
    std::vector<double> dense = all_levels(h);
    dense.resize(30);
    INFO("c = " << c.transpose() << ", " << lanczos.method);
    CHECK(max_difference(lanczos.values, dense) < 1e-10);
  }
}

TEST_CASE("quantum: terms that are not potentials of Gamma are refused", "[quantum]") {
  for (const char* name : {"stiff_damped_spring", "cardan_lagrange_upright"}) {
    INFO(name);
    CHECK_THROWS_AS(quantum_top_of(lgi::testing::shipped_scene(name)), InputError);
  }
  const lgi::system::Scene magnet = lgi::testing::shipped_scene("magnetic_top");
  const QuantumTop top = quantum_top_of(magnet);  // a vertical field: V = −B μ·Γ
  CHECK(top.weight.isApprox(Eigen::Vector3d(0.0, 0.0, -1.0e-3 * 39.27)));
  CHECK(top.symmetry == TopSymmetry::symmetric_heavy);
  const std::string horizontal =
      "name = \"x\"\ndescription = \"x\"\n[body]\ninertia = [1.0, 1.0, 2.0]\n[magnetic]\n"
      "dipole_moment = [0.0, 0.0, 1.0]\nfield = [1.0, 0.0, 0.0]\n";
  CHECK_THROWS_WITH(quantum_top_of(parse_scene(horizontal, "h.toml")), Catch::Contains("[magnetic] field"));
}

}  // namespace test_quantum_blocks

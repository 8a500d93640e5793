// The rows of R a torque term reads (TermTraits::attitude_rows,
// torque_term.hpp): the RKMK schemes form only those rows of a stage attitude
// and fill the others with NaN (rkmk_pair_kernels.hpp's stage_attitude).
//   - every term's torque at an R whose undeclared rows are NaN is its torque
//     at the whole R, bit for bit (a term that reads more fails here);
//   - a model's rows are the union over its terms in use (Declared), a
//     magnet's narrowed by its field's zeros;
//   - stage_attitude forms the declared rows as times_exp does, and NaN rows;
//   - a term that reads a row it did not declare makes the run non-finite;
//   - the RKMK schemes give the same bits as with every row formed.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "integrators/schemes/commutator_free.hpp"
#include "integrators/schemes/crouch_grossman.hpp"
#include "integrators/schemes/rkmk.hpp"
#include "integrators/schemes/rkmk_adaptive.hpp"
#include "integrators/system/model.hpp"
#include "integrators/system/terms/callable_torque.hpp"

namespace test_attitude_rows {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using lie::Mat3;
using lie::Vec3;
using State = lie::SO3xR3;

namespace {

const double nan = std::numeric_limits<double>::quiet_NaN();

Mat3 with_rows(const Mat3& R, unsigned rows) {
  Mat3 out = R;
  for (int i = 0; i < 3; ++i)
    if (!((rows >> i) & 1u)) out.row(i).setConstant(nan);
  return out;
}

bool same_bits(const Vec3& a, const Vec3& b) {
  for (int i = 0; i < 3; ++i)
    if (std::signbit(a(i)) != std::signbit(b(i)) || !(a(i) == b(i))) return false;
  return true;
}

template <class Term>
void check_term(const Term& term, unsigned expected_rows, const char* name) {
  INFO(name);
  CHECK(system::attitude_rows_of(term) == expected_rows);
  CHECK((system::attitude_rows_of(term) & ~Term::traits.attitude_rows) == 0u);  // within the traits' bound
  for (const Vec3& xi : {Vec3(0.3, -0.7, 0.5), Vec3(1.0, 0.5, 0.0), Vec3(-1.5, 2.0, 1.2)}) {
    const Mat3 R = lie::exp_so3(xi);
    const Vec3 Pi(0.4, -1.2, 2.0), Omega(0.8, -0.8, 1.3);
    const Vec3 whole = term.torque(R, Pi, Omega, 0.7);
    const Vec3 declared = term.torque(with_rows(R, system::attitude_rows_of(term)), Pi, Omega, 0.7);
    REQUIRE(whole.allFinite());
    CHECK(same_bits(declared, whole));
  }
}

/// Gravity that claims to read no row of R: the lie the NaN rows expose.
struct UndeclaredGravity : system::GravityTerm {
  static constexpr system::TermTraits traits{.attitude_rows = 0};
  using GravityTerm::GravityTerm;
};

/// Gravity that declares every row: the reference for the bit-for-bit check.
struct AllRowsGravity : system::GravityTerm {
  static constexpr system::TermTraits traits{.may_be_conservative = true, .linear_in_attitude = true};
  using GravityTerm::GravityTerm;
};

State top_state(const system::Inertia& J) {
  return {lie::exp_so3(Vec3(0.6, 0.0, 0.0)), J.J * Vec3(0.4, -0.3, 3.0)};
}

template <class Scheme, class Model>
State run(Scheme scheme, const Model& model, State s, double h, int steps) {
  integrators::WorkCounters work;
  for (int k = 0; k < steps; ++k) {
    if constexpr (requires { scheme.attempt(model, s, 0.0, h, work); }) scheme.attempt(model, s, k * h, h, work, true);
    else scheme.step(model, s, k * h, h, work);
  }
  return s;
}

}  // namespace

TEST_CASE("each term's torque reads only the rows of R it declares", "[attitude-rows]") {
  check_term(system::GravityTerm(2.0, 9.81, Vec3(0.1, -0.2, 0.7)), 0b100, "gravity");
  check_term(system::HarmonicDriveTerm{Vec3(0.3, -0.1, 0.2), 2.0, 0.4}, 0b000, "drive");
  check_term(system::SpringTerm(3.0, 0.2, lie::exp_so3(Vec3(0.1, 0.2, -0.3))), 0b111, "spring");
  check_term(system::MagneticDipoleTerm{Vec3(0.1, 0.5, -0.2), Vec3(0.3, -0.4, 1.0)}, 0b111, "magnetic, any field");
  check_term(system::MagneticDipoleTerm{Vec3(0.1, 0.5, -0.2), Vec3(0.3, 0.0, 1.0)}, 0b101, "magnetic, B2 = 0");
  check_term(system::MagneticDipoleTerm{Vec3(0.1, 0.5, -0.2), Vec3(0.0, 0.0, 1e-3)}, 0b100, "magnetic, vertical");
  auto f = [](double t, const Mat3& R, const Vec3& Pi, const Vec3&) -> Vec3 { return t * R.col(0).cross(Pi); };
  check_term(system::CallableTorque<decltype(f)>{f}, 0b111, "callable");
}

TEST_CASE("a model reads the union of the rows of its terms in use", "[attitude-rows]") {
  system::SceneModel model;
  CHECK(model.attitude_rows() == 0u);  // nothing declared: a free body in the scene model
  std::get<system::Declared<system::HarmonicDriveTerm>>(model.terms).active = true;
  CHECK(model.attitude_rows() == 0u);
  std::get<system::Declared<system::GravityTerm>>(model.terms).active = true;
  CHECK(model.attitude_rows() == 0b100u);
  auto& magnet = std::get<system::Declared<system::MagneticDipoleTerm>>(model.terms);
  magnet.active = true;
  magnet.term = {Vec3(0.0, 0.0, -39.27), Vec3(0.0, 0.0, 1e-3)};  // a vertical field: row 2, as gravity
  CHECK(model.attitude_rows() == 0b100u);
  magnet.term.field = Vec3(1e-3, 0.0, 0.0);
  CHECK(model.attitude_rows() == 0b101u);
  CHECK(system::HeavyTop{}.attitude_rows() == 0b100u);
}

TEST_CASE("the magnet's field in the body is R transpose B to the bit, whatever B's zeros", "[attitude-rows]") {
  const Mat3 R = lie::exp_so3(Vec3(0.3, -0.7, 0.5));
  for (const Vec3& B : {Vec3(0.3, -0.4, 1.0), Vec3(0.3, 0.0, 1.0), Vec3(0.0, 0.0, 1e-3), Vec3(-2.0, 0.5, 0.0)}) {
    const system::MagneticDipoleTerm magnet{Vec3(0.1, 0.5, -0.2), B};
    CHECK(same_bits(magnet.field_in_body(R), Vec3(R.transpose() * B)));
  }
}

TEST_CASE("stage_attitude forms the declared rows as times_exp does and NaN elsewhere", "[attitude-rows]") {
  namespace d = integrators::rkmk_pair_detail;
  const Mat3 R = lie::exp_so3(Vec3(0.3, -0.7, 0.5));
  for (const Vec3& w : {Vec3(0.01, -0.02, 0.03), Vec3(0.5, 0.6, -0.4), Vec3(1.5, -1.0, 2.0)}) {
    const auto m = d::map_coefficients(w.squaredNorm());
    const Mat3 whole = d::times_exp(R, w.data(), m);
    for (unsigned rows = 0; rows < 8; ++rows) {
      Mat3 out;
      d::stage_attitude(R, w.data(), m, rows, out);
      for (int i = 0; i < 3; ++i) {
        INFO("rows " << rows << " row " << i);
        if ((rows >> i) & 1u) CHECK(((out.row(i).array() == whole.row(i).array()).all()));
        else CHECK(out.row(i).array().isNaN().all());
      }
    }
  }
}

TEST_CASE("a term that reads a row it did not declare makes the run non-finite", "[attitude-rows]") {
  const system::Inertia J = system::make_inertia(Vec3(0.5, 0.85, 1.0).asDiagonal().toDenseMatrix());
  system::RigidBody<UndeclaredGravity> model{J, {UndeclaredGravity(1.0, 1.0, Vec3(0, 0, 1))}};
  CHECK_FALSE(run(integrators::Rkmk4{}, model, top_state(J), 0.01, 3).Pi.allFinite());
  CHECK_FALSE(run(integrators::RkmkDop853{1e-10}, model, top_state(J), 0.01, 3).Pi.allFinite());
  CHECK_FALSE(run(integrators::Cf4{}, model, top_state(J), 0.01, 3).Pi.allFinite());
  CHECK_FALSE(run(integrators::Cg4a{}, model, top_state(J), 0.01, 3).Pi.allFinite());
}

TEST_CASE("RKMK, CF and CG schemes give the same bits with only the declared rows formed", "[attitude-rows]") {
  const system::Inertia J = system::make_inertia(Vec3(0.5, 0.85, 1.0).asDiagonal().toDenseMatrix());
  const system::RigidBody<system::GravityTerm> top{J, {system::GravityTerm(1.0, 1.0, Vec3(0.1, 0.0, 1.0))}};
  const system::RigidBody<AllRowsGravity> reference{J, {AllRowsGravity(1.0, 1.0, Vec3(0.1, 0.0, 1.0))}};
  REQUIRE(top.attitude_rows() == 0b100u);
  REQUIRE(reference.attitude_rows() == 0b111u);
  auto check = [&](auto scheme, double h, const char* name) {
    INFO(name);
    const State a = run(scheme, top, top_state(J), h, 50);
    const State b = run(scheme, reference, top_state(J), h, 50);
    CHECK(((a.R.array() == b.R.array()).all() && (a.Pi.array() == b.Pi.array()).all()));
  };
  check(integrators::Rkmk4{}, 0.01, "rkmk4");
  check(integrators::RkmkDop853{1e-10}, 0.05, "rkmk-dop853");
  check(integrators::RkmkDp54{1e-10}, 0.05, "rkmk-dp54 (FSAL: the last stage forms every row)");
  check(integrators::RkmkVerner65{1e-10}, 0.05, "rkmk-verner65");
  check(integrators::Cf4{}, 0.01, "cf4");
  check(integrators::Cg4a{}, 0.01, "cg4a");
  check(integrators::Cg3{}, 0.01, "cg3");
}

}  // namespace test_attitude_rows

// The Cardan tangent flow's derivative (integrators/core/torus_tangent_flow.hpp):
// Df(x) v from the field in dual numbers (integrators/system/dual.hpp,
// integrators/system/cardan_field.hpp) against a Richardson-extrapolated
// central difference, its linearity in v, and the dual evaluation's value
// part against the double field (docs/cardan.md §9.3).
#include <catch2/catch.hpp>

#include <array>
#include <cmath>

#include "integrators/system/cardan_field.hpp"
#include "integrators/system/dual.hpp"
#include "integrators/core/torus_tangent_flow.hpp"
#include "support/cardan_problems.hpp"

namespace test_cardan_tangent {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using system::Dual;
using system::Vec6;

namespace {

/// (f(x + hv) − f(x − hv)) / 2h, twice Richardson-extrapolated: error O(h⁶).
Vec6 richardson_derivative(const system::CardanTop& top, const Vec6& x, const Vec6& v, double h) {
  const auto central = [&](double d) -> Vec6 {
    return (top.field(system::unstack(x + d * v)) - top.field(system::unstack(x - d * v))) / (2.0 * d);
  };
  const Vec6 d1 = central(h), d2 = central(h / 2.0), d4 = central(h / 4.0);
  const Vec6 r1 = (4.0 * d2 - d1) / 3.0, r2 = (4.0 * d4 - d2) / 3.0;  // O(h⁴)
  return (16.0 * r2 - r1) / 15.0;
}

/// States of the test top: the test initial state, one near gimbal lock
/// (q2 = 0.15) and one with large momenta.
std::array<Vec6, 3> test_states(const system::CardanTop& top) {
  std::array<Vec6, 3> xs;
  xs[0] = system::stack(testing::cardan_test_initial(top));
  xs[1] = system::stack(top.from_rates(lie::Vec3(-1.0, 0.15, 2.0), lie::Vec3(0.3, 1.1, -2.0)));
  xs[2] = system::stack(top.from_rates(lie::Vec3(2.5, 2.2, -0.7), lie::Vec3(-4.0, 6.0, 20.0)));
  return xs;
}

}  // namespace

TEST_CASE("Dual numbers carry exact first derivatives", "[cardan][tangent]") {
  const Dual x(0.7, 1.0);
  const Dual y = sin(x) * cos(x) / (Dual(2.0) + x * x) - x;
  const double d = (std::cos(1.4) * (2.0 + 0.49) - 0.5 * std::sin(1.4) * 1.4) / ((2.0 + 0.49) * (2.0 + 0.49)) - 1.0;
  CHECK(y.a == Approx(0.5 * std::sin(1.4) / 2.49 - 0.7).epsilon(1e-15));
  CHECK(y.b == Approx(d).epsilon(1e-14));
}

TEST_CASE("The Cardan tangent rate is the exact directional derivative of the field", "[cardan][tangent]") {
  for (const double tilt : {0.0, 0.6}) {
    const system::CardanTop top = testing::cardan_test_top(tilt);
    for (const Vec6& x : test_states(top)) {
      for (int i = 0; i < 4; ++i) {
        Vec6 v;
        v << 0.3, -0.2, 0.5, 0.1, 0.4, -0.6;
        if (i > 0) v = Vec6::Unit(i + 1) + 0.1 * v;
        const Vec6 exact = integrators::torus::torus_tangent_rate(top, x, v);
        const Vec6 fd = richardson_derivative(top, x, v, 2e-2);
        INFO("tilt " << tilt << ", x = " << x.transpose() << ", v = " << v.transpose());
        CHECK((exact - fd).norm() < 1e-9 * fd.norm());
      }
    }
  }
}

TEST_CASE("The exact tangent rate is linear in v and its value part is the field", "[cardan][tangent]") {
  const system::CardanTop top = testing::cardan_test_top(0.6);
  for (const Vec6& x : test_states(top)) {
    Vec6 v, w;
    v << 0.3, -0.2, 0.5, 0.1, 0.4, -0.6;
    w << -1.0, 0.7, 0.2, 2.0, -0.3, 0.9;
    const Vec6 dv = integrators::torus::torus_tangent_rate(top, x, v);
    const Vec6 dw = integrators::torus::torus_tangent_rate(top, x, w);
    const Vec6 dvw = integrators::torus::torus_tangent_rate(top, x, Vec6(2.0 * v - 3.0 * w));
    CHECK((dvw - (2.0 * dv - 3.0 * dw)).norm() < 1e-14 * (2.0 * dv.norm() + 3.0 * dw.norm()));
    CHECK(integrators::torus::torus_tangent_rate(top, x, Vec6(Vec6::Zero())).isZero(0.0));

    // The dual evaluation's value part is the field to round-off (not bit
    // for bit: Eigen vectorises the double products, not the dual ones; the
    // tangent step therefore advances the state with the double field).
    using system::cardan_detail::Vec3T;
    const Vec3T<Dual> q(Dual(x[0], v[0]), Dual(x[1], v[1]), Dual(x[2], v[2]));
    const Vec3T<Dual> p(Dual(x[3], v[3]), Dual(x[4], v[4]), Dual(x[5], v[5]));
    const auto f = system::cardan_detail::field(top, q, p);
    const Vec6 value = top.field(system::unstack(x));
    for (int k = 0; k < 6; ++k) CHECK(std::abs(f[k].a - value[k]) < 1e-14 * value.norm());
  }
}

}  // namespace test_cardan_tangent

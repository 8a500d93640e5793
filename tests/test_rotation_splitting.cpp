// split-axes and split-symmetric (integrators/schemes/split_axes.hpp,
// split_symmetric.hpp) and their closed-form sub-flows
// (integrators/schemes/rotation_flows.hpp). What the generic suites do not check:
//  - sin_cos agrees with the C library to a few ulp;
//  - each axis flow is the exact flow of ½ c Π_i² (against the exact free
//    flow of a body spinning about that axis), and flows of one axis merge;
//  - a free body spinning about a principal axis, and (split-symmetric) any
//    free body with two equal moments, is integrated exactly, at any step;
//  - a non-diagonal inertia tensor gives the diagonal body's trajectory in
//    rotated coordinates;
//  - the free body's energy error stays bounded, with no drift (1e5 steps);
//  - the compositions merge their outer rotations (the same result as
//    composing whole steps).
// Order, symmetry, the conservation claims, the Kovalevskaya integral and
// allocations are the generic suites' (test_stated_orders,
// test_composition, test_scheme_properties, test_allocations).
#include <catch2/catch.hpp>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "integrators/schemes/composition.hpp"
#include "integrators/schemes/rotation_flows.hpp"
#include "integrators/schemes/split_axes.hpp"
#include "integrators/schemes/split_symmetric.hpp"
#include "integrators/system/free_body_exact.hpp"
#include "integrators/system/model.hpp"
#include "support/registered_run.hpp"
#include "support/shipped_scene.hpp"

namespace test_rotation_splitting {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using lie::Mat3;
using lie::Vec3;

namespace {

system::FreeBody free_body(const Mat3& J) {
  system::FreeBody body;
  body.inertia = system::make_inertia(J);
  return body;
}

double distance(const system::State& a, const system::State& b) {
  return std::max(lie::geodesic_distance(a.R, b.R), (a.Pi - b.Pi).norm() / std::max(1.0, b.Pi.norm()));
}

template <class Scheme, class Model>
system::State integrate(const Model& model, system::State x, double h, int steps) {
  Scheme scheme;
  integrators::WorkCounters work;
  scheme.start(model, x, 0.0);
  for (int k = 0; k < steps; ++k) scheme.step(model, x, k * h, h, work);
  return x;
}

}  // namespace

TEST_CASE("sin_cos agrees with the C library to a few ulp", "[rotation-splitting]") {
  double worst = 0.0;
  for (int k = -20000; k <= 20000; ++k) {
    const double x = 1e-4 * k + 1e-9 * (k % 7);  // [−2, 2]: the Taylor range and the reduced one
    const auto sc = integrators::rotation_flows::sin_cos(x);
    worst = std::max({worst, std::abs(sc.sin - std::sin(x)), std::abs(sc.cos - std::cos(x))});
  }
  INFO("largest difference " << worst);
  CHECK(worst <= 2.0 * std::numeric_limits<double>::epsilon());
  for (double x : {1e3 + 0.1, -7.5e4, 2e5, -1e300}) {
    const auto sc = integrators::rotation_flows::sin_cos(x);
    CHECK(std::abs(sc.sin - std::sin(x)) <= 2.0 * std::numeric_limits<double>::epsilon());
    CHECK(std::abs(sc.cos - std::cos(x)) <= 2.0 * std::numeric_limits<double>::epsilon());
  }
  const auto tiny = integrators::rotation_flows::sin_cos(1e-200);
  CHECK(tiny.sin == 1e-200);
  CHECK(tiny.cos == 1.0);
}

TEST_CASE("an axis flow is the exact flow of a spin about that axis, and merges", "[rotation-splitting]") {
  const system::FreeBody body = free_body(Vec3(1.0, 2.0, 3.0).asDiagonal());
  const integrators::rotation_flows::PrincipalAxisFlows flows(body.inertia);
  for (int axis = 0; axis < 3; ++axis) {
    system::State x0;
    x0.R = lie::exp_so3(Vec3(0.3, -0.7, 0.2));
    x0.Pi = Vec3::Zero();
    x0.Pi(axis) = 2.5;
    const double t = 1.7;
    system::State x = x0;
    flows.flow(x, axis, 1.0 / body.inertia.principal(axis), t);
    const system::State exact = system::FreeBodyExactFlow(body.inertia, x0).at(t);
    INFO("axis " << axis);
    CHECK(distance(x, exact) <= 1e-14);
    // flow(a) ∘ flow(b) = flow(a + b) from a general state
    system::State y = x0, z = x0;
    y.Pi = z.Pi = Vec3(0.4, -1.1, 0.8);
    flows.flow(y, axis, 0.7, 0.3);
    flows.flow(y, axis, 0.7, -1.1);
    flows.flow(z, axis, 0.7, -0.8);
    CHECK(distance(y, z) <= 1e-15);
    CHECK(y.Pi(axis) == Vec3(0.4, -1.1, 0.8)(axis));  // Π_i is not touched
  }
}

TEST_CASE("a spin about a principal axis is integrated exactly at any step", "[rotation-splitting]") {
  const system::FreeBody body = free_body(Vec3(0.5, 0.85, 1.0).asDiagonal());
  for (int axis = 0; axis < 3; ++axis) {
    system::State x0;
    x0.R = lie::exp_so3(Vec3(0.6, 0.1, -0.3));
    x0.Pi = Vec3::Zero();
    x0.Pi(axis) = 3.0;
    const system::State exact = system::FreeBodyExactFlow(body.inertia, x0).at(10.0);
    INFO("axis " << axis);
    CHECK(distance(integrate<integrators::SplitAxes>(body, x0, 0.5, 20), exact) <= 1e-13);
    CHECK(distance(integrate<integrators::SplitSymmetric>(body, x0, 0.5, 20), exact) <= 1e-13);
  }
}

TEST_CASE("split-symmetric is the exact flow of a free body with two equal moments", "[rotation-splitting]") {
  for (const Vec3& moments : {Vec3(2.0, 2.0, 1.0), Vec3(1.0, 3.0, 3.0), Vec3(3.0, 1.0, 3.0)}) {
    const system::FreeBody body = free_body(moments.asDiagonal());
    system::State x0;
    x0.R = lie::exp_so3(Vec3(0.2, 0.5, -0.4));
    x0.Pi = Vec3(0.7, -1.3, 2.1);
    const system::State exact = system::FreeBodyExactFlow(body.inertia, x0).at(10.0);
    INFO("moments " << moments.transpose());
    CHECK(distance(integrate<integrators::SplitSymmetric>(body, x0, 0.25, 40), exact) <= 1e-13);
  }
}

TEST_CASE("a non-diagonal inertia gives the diagonal body's motion in rotated coordinates", "[rotation-splitting]") {
  // J = Q D Qᵀ: with R' = R Q and Π' = QᵀΠ the body moves as the one with J = D.
  const Mat3 Q = lie::exp_so3(Vec3(0.4, -0.9, 0.3));
  const Vec3 D(0.6, 1.3, 1.7);
  const system::FreeBody rotated = free_body(Q * D.asDiagonal() * Q.transpose());
  REQUIRE(!rotated.inertia.diagonal);
  const system::FreeBody diagonal = free_body(D.asDiagonal());
  system::State x0;
  x0.R = lie::exp_so3(Vec3(0.1, 0.2, 0.3));
  x0.Pi = Vec3(1.2, -0.4, 0.9);
  const system::State x0_diagonal{x0.R * Q, Q.transpose() * x0.Pi};
  auto compare = [&]<class Scheme>(const char* name) {
    const system::State a = integrate<Scheme>(rotated, x0, 0.05, 200);
    const system::State b = integrate<Scheme>(diagonal, x0_diagonal, 0.05, 200);
    INFO(name);
    CHECK(distance({a.R * Q, Q.transpose() * a.Pi}, b) <= 1e-12);
  };
  compare.template operator()<integrators::SplitAxes>("split-axes");
  compare.template operator()<integrators::SplitSymmetric>("split-symmetric");
}

TEST_CASE("the free body's energy error stays bounded, with no drift (1e5 steps)", "[rotation-splitting]") {
  const system::Scene scene = testing::shipped_scene("free_body_hlw");
  const system::AnyModel model = system::make_model(scene);
  const auto& body = std::get<system::FreeBody>(model);
  const double e0 = body.energy(scene.initial);
  for (const char* name : {"split-axes", "split-symmetric"}) {
    // The largest relative energy error over each half of 1e5 steps of 0.05 (t = 5000).
    class Halves final : public integrators::Observer {
     public:
      Halves(const system::FreeBody& b, double e, double t_half) : body_(b), e0_(e), t_half_(t_half) {}
      void observe(std::int64_t, double t, const system::State& s) override {
        double& half = t <= t_half_ ? first : second;
        half = std::max(half, std::abs(body_.energy(s) - e0_) / e0_);
      }
      double first = 0.0, second = 0.0;

     private:
      const system::FreeBody& body_;
      double e0_, t_half_;
    } halves(body, e0, 2500.0);
    const auto run = testing::run_registered(testing::registered_scheme(name), model, scene.initial, 5000.0, 0.05,
                                             &halves, 10);
    REQUIRE(run.stats.ok);
    std::cout << name << " on free_body_hlw, 1e5 steps of 0.05: energy error max " << halves.first
              << " (first half), " << halves.second << " (second half)\n";
    INFO(name << ": " << halves.first << " then " << halves.second);
    CHECK(halves.first < 1e-2);
    CHECK(halves.second < 1.5 * halves.first);
  }
}

TEST_CASE("compositions merge the outer rotations of neighbouring stages", "[rotation-splitting][composition]") {
  // Composition<Base> through outer/inner equals the plain product of the
  // base's steps Φ_{γ_s h} ∘ ⋯ ∘ Φ_{γ_1 h}, on a heavy top.
  const system::Scene scene = testing::shipped_scene("heavy_top_hlw");
  const auto model = std::get<system::SceneModel>(system::make_model(scene));
  auto check = [&]<class Base>(const char* name) {
    system::State merged = scene.initial, plain = scene.initial;
    integrators::Composition<Base, tableaus::kahan_li8> composed;
    Base base;
    integrators::WorkCounters work;
    composed.start(model, merged, 0.0);
    base.start(model, plain, 0.0);
    const double h = 0.1;
    for (int k = 0; k < 20; ++k) {
      composed.step(model, merged, k * h, h, work);
      double t = k * h;
      for (double g : tableaus::kahan_li8.gamma) {
        base.step(model, plain, t, g * h, work);
        t += g * h;
      }
    }
    INFO(name);
    CHECK(distance(merged, plain) <= 1e-13);
  };
  check.template operator()<integrators::SplitAxes>("split-axes");
  check.template operator()<integrators::SplitSymmetric>("split-symmetric");
}

}  // namespace test_rotation_splitting

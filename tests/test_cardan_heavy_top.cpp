// Cross-checks between the Cardan top on T³ and the heavy top on SO(3)
// (docs/cardan.md §8). With massless rings and a vertical outer axis the
// Cardan angles are the ZXZ chart of SO(3), so the Cardan flow is the heavy
// top's flow in that chart:
//  - on shipped heavy-top scenes (away from sin q2 = 0), cardan-dp54 at
//    tol 1e-12 and lgi's rkmk4 (dt 1e-4) against Boost's rkf78 at 1e-14
//    (tests/support/reference_solution.hpp): the same attitude and Π;
//  - cardan-midpoint and cardan-rk4 at dt 1e-3 agree with it to their own
//    accuracy;
//  - near gimbal lock (heavy_top_trindade_singular: θ passes near π):
//    with massless rings the Cardan rates grow like 1/sin q2 and the
//    adaptive scheme's step shrinks with them; massive rings keep M(q)
//    regular, the rates bounded, and change the motion.
#include <catch2/catch.hpp>
#include <cmath>
#include <iostream>

#include "experiments/io/scene_suspension.hpp"
#include "integrators/system/model.hpp"
#include "lie/charts.hpp"
#include "support/cardan_problems.hpp"
#include "support/reference_solution.hpp"
#include "support/registered_run.hpp"
#include "support/shipped_scene.hpp"

namespace test_cardan_heavy_top {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;

namespace {

/// The Cardan top of an SO(3) scene: massless rings, vertical outer axis,
/// the state from the scene's (R0, Π0) through the ZXZ chart.
struct Pulled {
  system::CardanTop top;
  system::TorusState x0;
};

Pulled pull_back(const system::Scene& scene) {
  system::Scene s = scene;
  s.suspension = system::SuspensionParameters{};
  Pulled p{experiments::cardan_top(s), {}};
  const lie::EulerZXZ e = lie::euler_zxz_from_matrix(scene.initial.R).angles;
  const lie::Vec3 q(e.psi, e.theta, e.phi);
  const lie::Vec3 omega = scene.inertia.inverse() * scene.initial.Pi;
  p.x0 = p.top.from_rates(q, lie::euler_zxz_rates_from_omega(e, omega));
  return p;
}

double attitude_gap(const lie::Mat3& a, const lie::Mat3& b) { return lie::geodesic_distance(a, b); }

}  // namespace

TEST_CASE("massless rings, vertical axis: the Cardan top is the SO(3) heavy top", "[cardan][heavy_top]") {
  for (const char* name : {"heavy_top_trindade_1", "heavy_top_trindade_3", "kovalevskaya", "general_top_richter"}) {
    system::Scene scene = testing::shipped_scene(name);
    if (lie::euler_zxz_from_matrix(scene.initial.R).singular)  // Richter's top starts at the identity: tilt it
      scene.initial.R = lie::matrix_from_euler_zxz({0.2, 0.9, -0.4});
    const double t_end = 2.0;
    const system::AnyModel model = system::make_model(scene);
    const system::State ref = std::visit(
        [&](const auto& m) { return testing::reference_solution(m, scene.initial, 0.0, t_end, 1e-14); }, model);
    const Pulled p = pull_back(scene);
    CHECK(attitude_gap(p.top.body_state(p.x0).R, scene.initial.R) <= 1e-14);
    CHECK((p.top.body_state(p.x0).Pi - scene.initial.Pi).norm() <= 1e-12 * scene.initial.Pi.norm());

    const testing::RegisteredRun so3 = testing::run_registered(testing::registered_scheme("rkmk4"), model,
                                                               scene.initial, t_end, 1e-4);
    for (const auto& [scheme, dt, tol, bound] :
         {std::tuple{"cardan-dp54", 0.0, 1e-12, 1e-9}, std::tuple{"cardan-rk4", 1e-3, 0.0, 1e-7},
          std::tuple{"cardan-midpoint", 1e-3, 0.0, 1e-3}}) {
      system::TorusState x = p.x0;
      REQUIRE(testing::run_torus(*integrators::find_cardan_scheme(scheme), p.top, x, t_end, dt, tol).ok);
      const lie::SO3xR3 b = p.top.body_state(x);
      const double gap = std::max(attitude_gap(b.R, ref.R), (b.Pi - ref.Pi).norm() / ref.Pi.norm());
      const double so3_gap =
          std::max(attitude_gap(so3.state.R, ref.R), (so3.state.Pi - ref.Pi).norm() / ref.Pi.norm());
      std::cout << name << ": " << scheme << " vs SO(3) rkf78 at t = 2: " << gap << " (lgi rkmk4 dt 1e-4: " << so3_gap
                << ")\n";
      INFO(name << " " << scheme);
      CHECK(gap <= bound);
      CHECK(so3_gap <= 1e-9);
    }
  }
}

TEST_CASE("gimbal lock: massless rings blow the Cardan rates up, massive rings keep them bounded",
          "[cardan][heavy_top]") {
  const system::Scene scene = testing::shipped_scene("heavy_top_trindade_singular");
  const Pulled massless = pull_back(scene);
  system::CardanTop massive = massless.top;
  massive.suspension.outer_inertia = 0.5;
  massive.suspension.inner_inertia = lie::Vec3(0.25, 0.5, 0.25);
  const system::TorusState x_massive = massive.from_rates(massless.x0.q, massless.top.velocity(massless.x0));
  const double t_end = 10.0;
  const system::AnyModel model = system::make_model(scene);
  const system::State ref = std::visit(
      [&](const auto& m) { return testing::reference_solution(m, scene.initial, 0.0, t_end, 1e-14); }, model);
  for (const auto& [label, top, x0] :
       {std::tuple{"massless rings", massless.top, massless.x0}, std::tuple{"massive rings", massive, x_massive}}) {
    system::TorusState x = x0;
    testing::KeepSamples all(true);
    const integrators::RunStats st =
        testing::run_torus(*integrators::find_cardan_scheme("cardan-dp54"), top, x, t_end, 0.0, 1e-10, &all);
    const bool massive_rings = std::string(label) == "massive rings";
    if (massive_rings) REQUIRE(st.ok);  // massless: reported, whatever happens at the lock
    double min_sin = 1.0, max_rate = 0.0, min_dt = 1e300;
    for (std::size_t k = 0; k < all.states.size(); ++k) {
      min_sin = std::min(min_sin, std::abs(std::sin(all.states[k].q[1])));
      max_rate = std::max(max_rate, top.velocity(all.states[k]).cwiseAbs().maxCoeff());
      if (k > 0) min_dt = std::min(min_dt, all.times[k] - all.times[k - 1]);
    }
    const double gap = attitude_gap(top.body_state(x).R, ref.R);
    std::cout << "gimbal lock, " << label << ": run ends at t = " << st.t_final
              << ", attitude gap there to the SO(3) heavy top at t = 10: " << gap << '\n';
    if (!massive_rings && st.ok) CHECK(gap <= 1e-6);
    if (massive_rings) CHECK(gap > 1e-2);  // the rings change the motion
    std::cout << "gimbal lock, " << label << ": min |sin q2| = " << min_sin << ", max |qdot| = " << max_rate
              << ", steps " << st.steps << ", smallest step " << min_dt << ", status: " << st.status << '\n';
    if (massive_rings) CHECK(max_rate < 50.0);
  }
}

TEST_CASE("the outer angle's momentum: an integral for a vertical axis, not for a tilted one", "[cardan][heavy_top]") {
  const auto& scheme = *integrators::find_cardan_scheme("cardan-midpoint");
  for (double tilt : {0.0, 0.3}) {
    const system::CardanTop top = testing::cardan_test_top(tilt);
    system::TorusState x = testing::cardan_test_initial(top);
    const double p10 = x.p[0];
    testing::KeepSamples all(true);
    REQUIRE(testing::run_torus(scheme, top, x, 50.0, 0.01, 0.0, &all).ok);
    double drift = 0.0;
    for (const auto& y : all.states) drift = std::max(drift, std::abs(y.p[0] - p10));
    std::cout << "tilt " << tilt << ": max |p1 - p1(0)| over t = 50 (cardan-midpoint, dt 0.01) = " << drift
              << " (p1(0) = " << p10 << ")\n";
    if (tilt == 0.0) CHECK(drift <= 1e-12);
    else CHECK(drift > 1e-2);
  }
}

}  // namespace test_cardan_heavy_top

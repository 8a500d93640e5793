// Events in the one time loop (RunConfig::events, integrators/core/events.hpp):
//  - on the free body, where the crossing times follow from the exact flow,
//    the exact scheme's crossings of Π1 = 0 are located to ≤ 1e-12 in time,
//    and a 4th-order scheme's to its global error;
//  - the direction filter keeps rising or falling crossings only;
//  - a run with events takes the same steps to the same final state, bit for
//    bit, as one without (location steps are taken on copies);
//  - the adaptive loop locates crossings too, on the dense output of the
//    pairs that have one: as accurately as on their step map, for a fraction
//    of the field evaluations.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "integrators/registry/registry.hpp"
#include "integrators/system/free_body_exact.hpp"
#include "support/shipped_scene.hpp"

namespace test_events {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;

namespace {

/// g = Π_k − value, with a direction filter.
class MomentumComponent final : public integrators::EventFunctions {
 public:
  MomentumComponent(int k, int direction) : k_(k), direction_(direction) {}
  int count() const override { return 1; }
  double value(int, double, const system::State& x) const override { return x.Pi(k_); }
  int direction(int) const override { return direction_; }

 private:
  int k_, direction_;
};

class Hits final : public integrators::Observer {
 public:
  void observe(std::int64_t, double, const system::State&) override {}
  void on_event(const integrators::EventHit& hit) override { hits.push_back(hit); }
  std::vector<integrators::EventHit> hits;
};

struct Run {
  integrators::RunStats stats;
  system::State final_state;
  std::vector<integrators::EventHit> hits;
};

Run run(const char* scheme, const system::Scene& scene, double dt, double tol, double t_end,
        const integrators::EventFunctions* events,
        integrators::EventLocation location = integrators::EventLocation::dense_output) {
  const auto* info = integrators::find_scheme(scheme);
  REQUIRE(info != nullptr);
  const system::AnyModel model = system::make_model(scene);
  integrators::RunConfig cfg;
  cfg.t_end = t_end;
  cfg.dt = dt;
  cfg.tol = tol;
  cfg.save_every = 1000000;
  cfg.events = events;
  cfg.event_location = location;
  Run r;
  r.final_state = scene.initial;
  Hits observer;
  r.stats = info->run(model, r.final_state, cfg, observer);
  r.hits = observer.hits;
  return r;
}

/// The zeros of Π_k(t) of the exact flow in (0, t_end], by bisection to round-off on a grid of 1e-3.
std::vector<double> exact_zeros(const system::Scene& scene, int k, double t_end) {
  const system::FreeBodyExactFlow flow(system::make_inertia(scene.inertia), scene.initial);
  auto g = [&](double t) { return flow.at(t).Pi(k); };
  std::vector<double> zeros;
  const double h = 1e-3;
  for (double a = 0.0; a < t_end; a += h) {
    double lo = a, hi = std::min(a + h, t_end), glo = g(lo), ghi = g(hi);
    if (!((glo < 0.0 && ghi >= 0.0) || (glo > 0.0 && ghi <= 0.0))) continue;
    for (int i = 0; i < 200 && hi - lo > 0.0; ++i) {
      const double m = 0.5 * (lo + hi);
      if (m == lo || m == hi) break;
      const double gm = g(m);
      if ((gm < 0.0) == (glo < 0.0) && gm != 0.0) lo = m, glo = gm;
      else hi = m;
    }
    zeros.push_back(hi);
  }
  return zeros;
}

double largest_time_error(const std::vector<integrators::EventHit>& hits, const std::vector<double>& zeros) {
  REQUIRE(hits.size() == zeros.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < hits.size(); ++i) worst = std::max(worst, std::abs(hits[i].t - zeros[i]));
  return worst;
}

}  // namespace

TEST_CASE("crossings of Pi1 = 0 on the free body are located to round-off on the exact flow", "[events]") {
  const auto scene = testing::shipped_scene("free_body_hlw");
  const MomentumComponent both(0, 0);
  const Run exact = run("exact", scene, 0.1, 0.0, 30.0, &both);
  REQUIRE(exact.stats.ok);
  const auto zeros = exact_zeros(scene, 0, 30.0);
  REQUIRE(zeros.size() >= 6);
  const double err = largest_time_error(exact.hits, zeros);
  INFO("exact scheme: " << zeros.size() << " crossings, largest time error " << err);
  CHECK(err <= 1e-12);
  for (const auto& hit : exact.hits) CHECK(std::abs(hit.state.Pi(0)) <= 1e-13);

  // A 4th-order scheme finds the same crossings to its global error (h^4).
  const Run rk = run("rkmk4", scene, 1e-2, 0.0, 30.0, &both);
  const double err_rk = largest_time_error(rk.hits, zeros);
  INFO("rkmk4 dt 1e-2: largest time error " << err_rk);
  CHECK(err_rk <= 1e-6);
}

TEST_CASE("the direction filter keeps rising or falling crossings", "[events]") {
  const auto scene = testing::shipped_scene("free_body_hlw");
  const MomentumComponent both(0, 0), rising(0, 1), falling(0, -1);
  const Run all = run("rkmk4", scene, 1e-2, 0.0, 30.0, &both);
  const Run up = run("rkmk4", scene, 1e-2, 0.0, 30.0, &rising);
  const Run down = run("rkmk4", scene, 1e-2, 0.0, 30.0, &falling);
  CHECK(up.hits.size() + down.hits.size() == all.hits.size());
  for (const auto& h : up.hits) CHECK(h.direction == 1);
  for (const auto& h : down.hits) CHECK(h.direction == -1);
  REQUIRE(!up.hits.empty());
  REQUIRE(!down.hits.empty());
}

TEST_CASE("events do not change the run's steps or final state", "[events]") {
  const auto scene = testing::shipped_scene("kovalevskaya");
  const MomentumComponent both(2, 0);
  for (const char* scheme : {"rkmk4", "lgvi", "rkmk-gauss4", "rkmk-dp54", "rkmk-verner65", "rkmk-dop853",
                             "rkmk-verner87", "rkmk-verner98"}) {
    const Run with = run(scheme, scene, 1e-2, 1e-8, 20.0, &both);
    const Run without = run(scheme, scene, 1e-2, 1e-8, 20.0, nullptr);
    INFO(scheme);
    REQUIRE(with.stats.ok);
    CHECK(!with.hits.empty());
    CHECK(with.stats.steps == without.stats.steps);
    CHECK(with.final_state.R == without.final_state.R);
    CHECK(with.final_state.Pi == without.final_state.Pi);
  }
}

TEST_CASE("the adaptive loop locates crossings on its accepted steps", "[events]") {
  const auto scene = testing::shipped_scene("free_body_hlw");
  const MomentumComponent both(0, 0);
  const std::vector<double> zeros = exact_zeros(scene, 0, 30.0);
  for (const char* scheme : {"rkmk-dp54", "rkmk-verner65", "rkmk-dop853", "rkmk-verner87", "rkmk-verner98"}) {
    const Run dp = run(scheme, scene, 0.0, 1e-12, 30.0, &both);
    REQUIRE(dp.stats.ok);
    const double err = largest_time_error(dp.hits, zeros);
    INFO(scheme << " tol 1e-12: largest time error " << err);
    CHECK(err <= 1e-8);
  }
}

TEST_CASE("the pairs with dense output locate crossings on their interpolant", "[events]") {
  const auto scene = testing::shipped_scene("free_body_hlw");
  const MomentumComponent both(0, 0);
  const std::vector<double> zeros = exact_zeros(scene, 0, 30.0);
  using integrators::EventLocation;
  for (const char* scheme : {"rkmk-verner65", "rkmk-dop853", "rkmk-verner87", "rkmk-verner98"}) {
    CHECK(integrators::find_scheme(scheme)->properties.dense_output);
    const Run dense = run(scheme, scene, 0.0, 1e-12, 30.0, &both, EventLocation::dense_output);
    const Run map = run(scheme, scene, 0.0, 1e-12, 30.0, &both, EventLocation::step_map);
    const Run none = run(scheme, scene, 0.0, 1e-12, 30.0, nullptr);
    REQUIRE(dense.stats.ok);
    REQUIRE(map.stats.ok);
    REQUIRE(dense.hits.size() == map.hits.size());
    const double err_dense = largest_time_error(dense.hits, zeros), err_map = largest_time_error(map.hits, zeros);
    double apart = 0.0, residual = 0.0;
    for (std::size_t i = 0; i < dense.hits.size(); ++i) {
      apart = std::max(apart, std::abs(dense.hits[i].t - map.hits[i].t));
      residual = std::max(residual, std::abs(dense.hits[i].state.Pi(0)));
      CHECK(dense.hits[i].step == map.hits[i].step);
      CHECK(dense.hits[i].direction == map.hits[i].direction);
    }
    const auto extra = [&](const Run& r) { return r.stats.work.rhs_evaluations - none.stats.work.rhs_evaluations; };
    const auto n = static_cast<std::int64_t>(dense.hits.size());
    INFO(scheme << ": " << n << " crossings; time error " << err_dense << " (dense output), " << err_map
                << " (step map), apart " << apart << "; residual " << residual << "; extra evaluations "
                << extra(dense) << " (dense output), " << extra(map) << " (step map)");
    // The same steps and final state, bit for bit, whichever way crossings are located.
    CHECK(dense.stats.steps == none.stats.steps);
    CHECK(dense.final_state.R == none.final_state.R);
    CHECK(dense.final_state.Pi == none.final_state.Pi);
    CHECK(err_dense <= 1e-8);
    CHECK(apart <= 1e-9);
    CHECK(residual <= 1e-13);
    // At most the interpolant's extra stages (≤ 10) per crossing; a step-map search costs a step per iteration.
    CHECK(extra(dense) <= 10 * n);
    CHECK(3 * extra(dense) <= extra(map));
  }
}

}  // namespace test_events

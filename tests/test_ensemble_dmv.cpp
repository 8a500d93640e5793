// The ensemble kernel of the DMV schemes, dmv, lgvi and the preprocessed
// dmv-pre* (integrators/ensemble/dmv_kernel.hpp,
// docs/ensemble.md): every lane is bit for bit the scalar scheme's
// trajectory, on every instruction set this CPU has, through the steps the
// kernel takes and those it leaves to the scalar scheme (the first six, a
// change of step length, a refused step); the ensemble loop gives each lane
// the registry's run; a step allocates nothing.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "tests/ensemble_test_support.hpp"
#include "support/allocation_count.hpp"  // heap allocations: the global operator new counts them
#include "experiments/io/scene_reader.hpp"
#include "integrators/ensemble/ensemble_loop.hpp"
#include "integrators/schemes/moser_veselov_preprocessed.hpp"
#include "integrators/registry/registry.hpp"

namespace test_ensemble_dmv {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
namespace ensemble = lgi::integrators::ensemble;
using integrators::State;
using namespace lgi::ensemble_test;

namespace {

/// The step lengths of the lane test: a run of equal steps (the kernel's), a
/// change of length (the predictor starts anew), one step far too long (the
/// scheme refuses it), and equal steps again.
std::vector<double> step_lengths(double h) {
  std::vector<double> out(120, h);
  for (int k = 0; k < 20; ++k) out.push_back(0.5 * h);
  out.push_back(1e5 * h);
  for (int k = 0; k < 40; ++k) out.push_back(h);
  return out;
}

/// n trajectories stepped together and one at a time by Scheme, compared after every step.
template <class Scheme>
void check_lanes(const system::Scene& scene, const char* name, ensemble::Isa isa, int n) {
  const system::AnyModel any = system::make_model(scene);
  const auto& model = std::get<system::FreeBody>(any);
  auto e = ensemble::EnsembleStepper::make(name, any, isa);
  REQUIRE(e);
  REQUIRE(e->has_memory());
  std::vector<State> scalar = initial_states(scene.initial, n, 23u + static_cast<unsigned>(n));
  std::vector<Scheme> schemes(static_cast<std::size_t>(n));
  for (int l = 0; l < e->lanes(); ++l) e->start_lane(l, scalar[static_cast<std::size_t>(l < n ? l : 0)], 0.0);
  for (int l = 0; l < n; ++l) schemes[static_cast<std::size_t>(l)].start(model, scalar[static_cast<std::size_t>(l)], 0.0);
  int mismatches = 0, status_mismatches = 0, refused = 0;
  double t = 0.0;
  const std::int64_t kernel_before = e->kernel_lane_steps();
  for (const double h : step_lengths(scene.dt.value_or(1e-2))) {
    e->step(t, h);
    for (int l = 0; l < n; ++l) {
      State& s = scalar[static_cast<std::size_t>(l)];
      integrators::WorkCounters work;
      const integrators::StepStatus st = schemes[static_cast<std::size_t>(l)].step(model, s, t, h, work);
      refused += st.converged ? 0 : 1;
      const ensemble::LaneOutcome& o = e->outcome(l);
      status_mismatches += o.status.converged != st.converged || o.status.iterations != st.iterations ||
                           o.work.rhs_evaluations != work.rhs_evaluations;
      State lane;
      e->get_lane(l, lane);
      mismatches += same_bits(lane, s) ? 0 : 1;
    }
    t += h;
  }
  const std::int64_t by_kernel = e->kernel_lane_steps() - kernel_before;
  INFO(name << ", " << ensemble::isa_name(isa) << ", " << n << " of " << e->lanes() << " lanes; " << by_kernel
            << " lane steps by the kernel");
  CHECK(mismatches == 0);
  CHECK(status_mismatches == 0);
  CHECK(refused == n);  // the long step, in every lane
  // Most steps go through the kernel; the first six of each run of equal steps do not.
  CHECK(by_kernel >= static_cast<std::int64_t>(n) * (114 + 14 + 34));
}

}  // namespace

TEST_CASE("ensemble lanes are dmv, lgvi and dmv-pre bit for bit on every instruction set", "[ensemble][dmv]") {
  for (const char* name : {"free_body_hlw", "dzhanibekov_book_axis2", "dzhanibekov_book_axis1"}) {
    const system::Scene scene = shipped(name);
    INFO(name);
    REQUIRE(ensemble::unsupported_reason("dmv-pre10", system::make_model(scene)).empty());
    for (const ensemble::Isa isa : ensemble::available_isas()) {
      const int lanes = ensemble::isa_lanes(isa);
      for (const int n : {1, 3, lanes}) {
        check_lanes<integrators::DmvPre10>(scene, "dmv-pre10", isa, n);
        check_lanes<integrators::DmvPre4>(scene, "dmv-pre4", isa, n);
        check_lanes<integrators::Dmv>(scene, "dmv", isa, n);
        check_lanes<integrators::Lgvi>(scene, "lgvi", isa, n);
      }
    }
  }
}

TEST_CASE("what has no dmv-pre ensemble kernel says why", "[ensemble][dmv]") {
  const system::AnyModel top = system::make_model(shipped("heavy_top_trindade_1"));
  CHECK_THAT(ensemble::unsupported_reason("dmv-pre10", top), Catch::Contains("torques"));
  CHECK_FALSE(ensemble::EnsembleStepper::make("dmv-pre10", top, ensemble::Isa::baseline));
  const system::Scene tilted = experiments::parse_scene(
      "name = \"tilted\"\n[body]\ninertia_tensor = [[1.0, 0.1, 0.0], [0.1, 1.5, 0.0], [0.0, 0.0, 2.0]]\n"
      "[initial]\nangular_velocity = [0.1, 1.0, 0.2]\n",
      "tilted.toml");
  CHECK_THAT(ensemble::unsupported_reason("dmv-pre10", system::make_model(tilted)), Catch::Contains("non-diagonal"));
  CHECK_THAT(ensemble::unsupported_reason("lgvi", top), Catch::Contains("torques"));
  CHECK(ensemble::has_kernel("dmv-pre6"));
  CHECK(ensemble::has_kernel("dmv"));
  CHECK_FALSE(ensemble::has_kernel("cf4"));
}

namespace {

/// Π1 = 0 both ways.
struct MomentumZero final : integrators::EventFunctions {
  int count() const override { return 1; }
  double value(int, double, const State& x) const override { return x.Pi(0); }
  int direction(int) const override { return 0; }
};

}  // namespace

TEST_CASE("the ensemble loop gives each dmv-pre lane the scalar loop's run", "[ensemble][dmv]") {
  const system::Scene body = shipped("free_body_hlw");
  MomentumZero zero;
  integrators::RunConfig cfg = loop_config(&zero);
  std::vector<State> initial = initial_states(body.initial, 16, 5);
  SECTION("samples every 7 steps and crossings: dmv-pre10, dmv and lgvi") {
    for (const char* scheme : {"dmv-pre10", "dmv", "lgvi"}) check_loop(scheme, body, cfg, initial);
  }
  SECTION("output times, and dmv-pre6") {
    cfg.output_times = &loop_output_times;
    check_loop("dmv-pre6", body, cfg, initial);
  }
  SECTION("backward in time, a step that does not divide the span") {
    cfg.t_end = -2.005;
    check_loop("dmv-pre10", body, cfg, initial);
  }
  SECTION("lanes that fail: a blow-up and a step the scheme refuses; the others go on") {
    initial[1].Pi(2) = std::numeric_limits<double>::infinity();
    initial[4].Pi *= 1e3;  // |h Ω| > π: refused at the first step
    cfg.retry_halving = 2;
    check_loop("dmv-pre10", body, cfg, initial);
  }
  // Without events most steps observe nothing, and the loop only counts the kernel's.
  SECTION("without events: samples every 7 steps, a change of step length") {
    cfg.events = nullptr;
    cfg.t_end = 2.005;
    check_loop("dmv-pre10", body, cfg, initial);
    check_loop("lgvi", body, cfg, initial);
  }
  SECTION("without events: a lane refused, the others go on") {
    cfg.events = nullptr;
    initial[3].Pi *= 1e3;
    check_loop("dmv-pre10", body, cfg, initial);
  }
}

TEST_CASE("a dmv-pre ensemble step allocates nothing", "[ensemble][dmv][allocations]") {
  const system::Scene scene = shipped("free_body_hlw");
  const system::AnyModel model = system::make_model(scene);
  for (const ensemble::Isa isa : ensemble::available_isas()) {
    auto e = ensemble::EnsembleStepper::make("dmv-pre10", model, isa);
    REQUIRE(e);
    const std::vector<State> initial = initial_states(scene.initial, e->lanes(), 2);
    for (int l = 0; l < e->lanes(); ++l) e->start_lane(l, initial[static_cast<std::size_t>(l)], 0.0);
    const long before = lgi::testing::counted_allocations();
    for (int k = 0; k < 1000; ++k) e->step(k * 0.01, k < 500 ? 0.01 : 0.02);  // both kernel and scalar steps
    CHECK(lgi::testing::counted_allocations() == before);
  }
}

}  // namespace test_ensemble_dmv

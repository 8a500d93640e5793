// The ensemble as a mode of the registry entry (docs/ensemble.md, "What has a
// kernel"): every registered scheme whose facts declare a lane kernel runs in
// lanes bit for bit as the registry's scalar run, found from the registry
// alone (no list of names here or in the ensemble); a scheme without one, an
// unknown name and a scheme registered at run time get the registry's answer;
// `lgi schemes --json` names the kernel.
#include <catch2/catch.hpp>

#include <set>
#include <string>
#include <vector>

#include "experiments/cli/scheme_record.hpp"
#include "integrators/registry/register_scheme.hpp"
#include "integrators/registry/registry.hpp"
#include "integrators/schemes/rkmk.hpp"
#include "tests/ensemble_test_support.hpp"

namespace test_ensemble_registry {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
namespace ensemble = lgi::integrators::ensemble;
using integrators::LaneKernel;
using integrators::SchemeInfo;
using namespace lgi::ensemble_test;

namespace {

/// The shipped scenes the lane test tries each scheme on: a free body with
/// diagonal J, a heavy top, a top with a non-diagonal J, Kovalevskaya's top.
const std::vector<std::string> lane_scenes{"free_body_hlw", "heavy_top_trindade_1", "general_top_richter",
                                           "kovalevskaya"};

/// rkmk4's step under another name, its facts with or without the lane kernel:
/// schemes from outside lgi's tree, which no list of names can know.
template <bool Lanes>
struct RenamedRkmk4 : integrators::Rkmk4 {
  static constexpr integrators::SchemeFacts facts = [] {
    integrators::SchemeFacts f = integrators::Rkmk4::facts;
    f.lane_kernel = Lanes ? LaneKernel::rkmk4 : LaneKernel::none;
    return f;
  }();
};

void register_renamed() {
  if (!integrators::find_scheme("test-rk4-lanes"))
    integrators::register_scheme<RenamedRkmk4<true>>({.name = "test-rk4-lanes", .family = "RKMK"});
  if (!integrators::find_scheme("test-rk4-scalar"))
    integrators::register_scheme<RenamedRkmk4<false>>({.name = "test-rk4-scalar", .family = "RKMK"});
}

/// The scheme's lanes against its scalar runs on every lane scene it applies to; how many.
int check_on_lane_scenes(const SchemeInfo& s) {
  int scenes = 0;
  for (const std::string& name : lane_scenes) {
    const system::Scene scene = shipped(name);
    if (!ensemble::unsupported_reason(s, system::make_model(scene)).empty()) continue;
    INFO(s.name << " on " << name);
    check_loop(s.name.c_str(), scene, loop_config(nullptr), initial_states(scene.initial, 16, 41u));
    ++scenes;
  }
  return scenes;
}

}  // namespace

TEST_CASE("every scheme whose facts declare a lane kernel runs in lanes bit for bit as its scalar run") {
  register_renamed();
  std::set<LaneKernel> kernels;
  int schemes = 0;
  for (const SchemeInfo& s : integrators::scheme_registry()) {
    if (s.lanes.kernel == LaneKernel::none) continue;
    INFO(s.name);
    CHECK(ensemble::has_kernel(s));
    CHECK(s.lanes.run != nullptr);
    CHECK((s.lanes.fallback != nullptr) == (s.lanes.kernel == LaneKernel::dmv_diagonal));
    CHECK(check_on_lane_scenes(s) > 0);  // a kernel no shipped scene of the list can use is a dead claim
    kernels.insert(s.lanes.kernel);
    ++schemes;
  }
  // rkmk4, dmv, lgvi, dmv-pre4 … dmv-pre10 and test-rk4-lanes; both kernels.
  CHECK(schemes >= 8);
  CHECK(kernels == std::set<LaneKernel>{LaneKernel::rkmk4, LaneKernel::dmv_diagonal});
}

TEST_CASE("the ensemble asks the registry: no kernel, unknown names, schemes registered at run time") {
  register_renamed();
  const system::AnyModel free = system::make_model(shipped("free_body_hlw"));
  for (const SchemeInfo& s : integrators::scheme_registry()) {
    if (s.lanes.kernel != LaneKernel::none) continue;
    INFO(s.name);
    CHECK_FALSE(ensemble::has_kernel(s.name));
    CHECK_FALSE(ensemble::unsupported_reason(s, free).empty());
    CHECK_FALSE(ensemble::EnsembleStepper::make(s, free, ensemble::Isa::baseline));
  }
  CHECK(ensemble::unsupported_reason("no-such-scheme", free) ==
        "unknown scheme 'no-such-scheme' (lgi schemes lists them)");
  CHECK_FALSE(ensemble::has_kernel("no-such-scheme"));
  CHECK_FALSE(ensemble::EnsembleStepper::make("no-such-scheme", free, ensemble::Isa::baseline));
  // The registry's refusal of the scene comes first (dmv: free bodies only).
  const system::AnyModel top = system::make_model(shipped("heavy_top_trindade_1"));
  CHECK(ensemble::unsupported_reason("dmv", top) == integrators::unsupported_reason(*integrators::find_scheme("dmv"), top));
  // The same step under two new names: the facts decide, not the name.
  CHECK(ensemble::has_kernel("test-rk4-lanes"));
  CHECK_FALSE(ensemble::has_kernel("test-rk4-scalar"));
  CHECK(ensemble::unsupported_reason("test-rk4-scalar", free) == "no ensemble kernel for test-rk4-scalar");
  const auto e = ensemble::EnsembleStepper::make("test-rk4-lanes", free, ensemble::Isa::baseline);
  REQUIRE(e);
  CHECK(e->scheme() == "test-rk4-lanes");
  CHECK(e->rhs_per_step() == 4);
  CHECK_FALSE(e->has_memory());
}

TEST_CASE("lgi schemes --json names each scheme's lane kernel") {
  const auto lane_kernel = [](const char* name) {
    for (const auto& f : experiments::scheme_record(*integrators::find_scheme(name), std::nullopt))
      if (f.key == "lane_kernel") return f.value;
    FAIL("no lane_kernel field");
    return decltype(experiments::SchemeField::value){};
  };
  using Value = decltype(experiments::SchemeField::value);
  CHECK(lane_kernel("rkmk4") == Value{std::string("rkmk4")});
  CHECK(lane_kernel("dmv-pre10") == Value{std::string("dmv-diagonal")});
  CHECK(lane_kernel("cf4") == Value{});
  CHECK(lane_kernel("rkmk-cayley4") == Value{});  // RK4 in Cayley coordinates: not the kernel's step
  CHECK(lane_kernel("dmv@yoshida4") == Value{});  // a composition is not its base's step
}

}  // namespace test_ensemble_registry

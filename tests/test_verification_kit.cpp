// The verification kit (experiments/analysis/scheme_verification.hpp), the
// checks an out-of-tree scheme gets (docs/extending.md): it passes schemes
// whose facts hold (an explicit RKMK, a symmetric conserving variational
// scheme, an adaptive pair; every scheme of T³ × ℝ³ on the Cardan problems,
// and one built outside the registry), and fails each kind of false claim (a
// wrong order, symmetry, symplecticity, energy or p1 conservation, an
// invariant the Cardan top does not have), naming the check.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/allocation_count.hpp"  // heap allocations: the global operator new counts them
#include "experiments/analysis/scheme_verification.hpp"
#include "experiments/analysis/scheme_verification_cardan.hpp"
#include "integrators/registry/register_scheme.hpp"
#include "integrators/registry/torus_registry.hpp"
#include "integrators/schemes/rkmk.hpp"
#include "integrators/schemes/torus_explicit.hpp"
#include "support/registered_run.hpp"
#include "support/shipped_scene.hpp"

namespace test_verification_kit {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
namespace verification = experiments::verification;

namespace {

verification::Options options() {
  verification::Options o;
  o.scenes_dir = LGI_SCENES_DIR;
  o.allocation_count = &lgi::testing::counted_allocations;
  o.conservation_steps = 5000;
  return o;
}

verification::Report verified(const integrators::SchemeInfo& s) {
  const verification::Report r = verification::verify_scheme(s, options());
  verification::print_report(std::cout, r);
  return r;
}

bool failed(const verification::Report& r, const std::string& prefix) {
  return std::any_of(r.checks.begin(), r.checks.end(),
                     [&](const auto& c) { return !c.passed && c.name.rfind(prefix, 0) == 0; });
}

std::ptrdiff_t count_named(const verification::Report& r, const std::string& prefix) {
  return std::count_if(r.checks.begin(), r.checks.end(), [&](const auto& c) { return c.name.rfind(prefix, 0) == 0; });
}

/// A T³ scheme's report: every check on a Cardan problem (or on none, "-"), the state space named.
void check_cardan_report(const verification::Report& r) {
  CHECK(r.state_space == "T^3 x R^3");
  for (const auto& c : r.checks) {
    INFO(c.name << " on " << c.problem);
    CHECK((c.cardan || c.problem == "-"));
  }
}

}  // namespace

TEST_CASE("the verification kit passes schemes whose stated facts hold", "[verification]") {
  for (const char* name : {"rkmk4", "lgvi", "rkmk-dp54"}) {
    const verification::Report r = verified(testing::registered_scheme(name));
    INFO(name);
    CHECK(r.passed());
    CHECK(std::count_if(r.checks.begin(), r.checks.end(),
                        [](const auto& c) { return c.name.rfind("order", 0) == 0; }) >= 2);
    CHECK(std::any_of(r.checks.begin(), r.checks.end(),
                      [](const auto& c) { return c.name == "no allocation per step"; }));
  }
}

TEST_CASE("the verification kit fails false claims, naming them", "[verification]") {
  integrators::SchemeInfo liar = testing::registered_scheme("rkmk4");
  liar.name = "rkmk4-with-false-claims";
  liar.order = 5;
  liar.properties.symmetric = true;
  liar.properties.conserves_energy = true;
  const verification::Report r = verified(liar);
  CHECK_FALSE(r.passed());
  CHECK(failed(r, "order 5"));
  CHECK(failed(r, "symmetry"));
  CHECK(failed(r, "conserves energy"));
}

TEST_CASE("a slope above the stated order down to the floor is pre-asymptotic, not a pass", "[verification]") {
  using verification::OrderVerdict;
  // Errors falling by h^9 from 1e-6 to below the 1e-10 floor, for a stated order 8.
  std::vector<verification::ConvergencePoint> pts;
  for (double h = 0.5, e = 1e-6; e > 1e-11; h *= 0.8, e *= std::pow(0.8, 9.0)) pts.push_back({h, e});
  const verification::SlopeFit fit = verification::fit_finest(pts);
  REQUIRE(fit.points >= 3);
  CHECK(fit.slope == Approx(9.0));
  CHECK(verification::order_verdict(fit, pts, 8) == OrderVerdict::pre_asymptotic);
  CHECK(verification::order_verdict(fit, pts, 9) == OrderVerdict::shown);
  CHECK(verification::order_verdict(fit, pts, 10) == OrderVerdict::not_shown);  // below the stated order
  pts.pop_back();  // stopped above the floor: the asymptotic regime was not reached, nothing is excused
  CHECK(verification::order_verdict(verification::fit_finest(pts), pts, 8) == OrderVerdict::not_shown);
  // A processed composition is pre-asymptotic on the Kovalevskaya top and shows its order elsewhere.
  const verification::Report r = verified(testing::registered_scheme("split-axes@bcm-processed8"));
  CHECK(r.passed());
  CHECK(std::any_of(r.checks.begin(), r.checks.end(),
                    [](const auto& c) { return c.detail.rfind("pre-asymptotic", 0) == 0; }));
}

TEST_CASE("the verification kit fails a claim no problem of it supports", "[verification]") {
  integrators::SchemeInfo s = testing::registered_scheme("exact");
  s.name = "exact-claiming-vertical-momentum";
  s.properties.conserves_vertical_momentum = true;  // free body only: no heavy top can check it
  const verification::Report r = verified(s);
  CHECK(failed(r, "conserves Pi.Gamma"));
}

TEST_CASE("register_scheme adds an out-of-tree scheme type to the registry", "[verification][registry]") {
  // Kutta's RKMK3 under another name: the registry reads its facts, and it runs as rkmk3 does, bit for bit.
  integrators::register_scheme<integrators::Rkmk<tableaus::kutta3>>({.name = "rkmk3-registered", .family = "RKMK"});
  const integrators::SchemeInfo& added = testing::registered_scheme("rkmk3-registered");
  const integrators::SchemeInfo& rkmk3 = testing::registered_scheme("rkmk3");
  CHECK(added.order == 3);
  CHECK(added.reference == rkmk3.reference);
  const system::Scene scene = testing::shipped_scene("kovalevskaya");
  const system::AnyModel model = system::make_model(scene);
  const system::State a = testing::final_state_ok(added, model, scene.initial, 1.0, 1e-2);
  const system::State b = testing::final_state_ok(rkmk3, model, scene.initial, 1.0, 1e-2);
  CHECK(a.R == b.R);
  CHECK(a.Pi == b.Pi);
  CHECK_THROWS_AS(integrators::register_scheme<integrators::Rkmk<tableaus::kutta3>>({.name = "rkmk3", .family = "RKMK"}),
                  std::invalid_argument);
}

TEST_CASE("the verification kit passes every scheme of T^3 x R^3 on Cardan problems", "[verification][cardan]") {
  // From the registry: a T^3 scheme added later is verified here without further code.
  REQUIRE(!integrators::cardan_scheme_registry().empty());
  for (const integrators::SchemeInfo& s : integrators::cardan_scheme_registry()) {
    const verification::Report r = verified(s);
    INFO(s.name);
    CHECK(r.passed());
    check_cardan_report(r);
    CHECK(count_named(r, "order") >= 2);
    CHECK(count_named(r, "no allocation per step") == 2);
    if (s.properties.symmetric && !s.properties.adaptive) CHECK(count_named(r, "symmetry") == 2);
    if (s.properties.conserves_energy) CHECK(count_named(r, "conserves energy") >= 1);
    if (s.properties.conserves_vertical_momentum) CHECK(count_named(r, "conserves p1") >= 1);
  }
}

TEST_CASE("the verification kit verifies a T^3 scheme built outside the registry", "[verification][cardan]") {
  // Runge-Kutta on Kutta's third-order tableau on T^3: an entry made with cardan_entry, never registered.
  const integrators::SchemeInfo s =
      integrators::torus::cardan_entry<integrators::torus::TorusRk<tableaus::kutta3>>("cardan-rk3", "test");
  const verification::Report r = verified(s);
  CHECK(r.passed());
  check_cardan_report(r);
  CHECK(count_named(r, "order 3") == 2);
  CHECK(count_named(r, "conserves p1") == 1);  // only where the outer axis is vertical
}

TEST_CASE("the verification kit fails false claims of T^3 schemes, naming them", "[verification][cardan]") {
  integrators::SchemeInfo liar = *integrators::find_cardan_scheme("cardan-rk4");
  liar.name = "cardan-rk4-with-false-claims";
  liar.order = 5;
  liar.properties.symmetric = true;
  liar.properties.symplectic = true;
  liar.properties.conserves_energy = true;
  liar.properties.conserves_momentum_norm = true;  // the Cardan top has no |Pi| integral
  const verification::Report r = verified(liar);
  CHECK_FALSE(r.passed());
  check_cardan_report(r);
  CHECK(failed(r, "order 5"));
  CHECK(failed(r, "symmetry"));
  CHECK(failed(r, "symplectic"));
  CHECK(failed(r, "conserves energy"));
  CHECK(failed(r, "conserves |Pi|"));
  // The discrete gradient does not keep p1 (its correction has an O(h^3) component along q1: torus_implicit.hpp).
  integrators::SchemeInfo dg = *integrators::find_cardan_scheme("cardan-dg");
  dg.name = "cardan-dg-claiming-p1";
  dg.properties.conserves_vertical_momentum = true;
  const verification::Report r_dg = verified(dg);
  CHECK(failed(r_dg, "conserves p1"));
}

}  // namespace test_verification_kit

// The verification kit (experiments/analysis/scheme_verification.hpp), the
// checks an out-of-tree scheme gets (docs/extending.md): it passes schemes
// whose facts hold (an explicit RKMK, a symmetric conserving variational
// scheme, an adaptive pair), and fails each kind of false claim (a wrong
// order, symmetry, energy conservation), naming the check.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "experiments/analysis/allocation_counter.hpp"
#include "experiments/analysis/scheme_verification.hpp"
#include "integrators/registry/register_scheme.hpp"
#include "integrators/schemes/rkmk.hpp"
#include "support/registered_run.hpp"
#include "support/shipped_scene.hpp"

using namespace lgi;
namespace verification = experiments::verification;

namespace {

verification::Options options() {
  verification::Options o;
  o.scenes_dir = LGI_SCENES_DIR;
  o.allocation_count = &verification::counted_allocations;
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

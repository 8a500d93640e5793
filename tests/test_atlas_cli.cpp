// The atlas commands as a user runs them (issue 49 items 4-6):
//  - lgi bifurcation locates the changes of Grammel's class along a branch
//    (class_change rows, CSV column and stdout lines) and names the branches;
//  - lgi poincare --seeds: orbits from a CSV of section points or states, and
//    its refusals (bad header, off the level, with --ics, on a Cardan top);
//  - a Cardan top with a tilted outer axis: p1 is no integral, so simulate
//    reports no p1 error and poincare warns that --l only sets the initial p1;
//  - numbers echoed on stdout have 6 significant digits (l = 2.2, not
//    2.2000000000000002).
#include <catch2/catch.hpp>
#include <fstream>
#include <regex>
#include <string>

#include "support/run_command.hpp"

namespace test_atlas_cli {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using Catch::Matchers::Contains;
using namespace lgi;

namespace {

const std::string scenes = LGI_SCENES_DIR;

/// No decimal number in the text with more than 6 significant digits (2.2000000000000002 has 17).
bool six_digits(const std::string& text) {
  const std::regex number("[0-9]*\\.[0-9]+");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), number); it != std::sregex_iterator(); ++it) {
    std::string digits;
    for (const char c : it->str())
      if (c != '.' && !(digits.empty() && c == '0')) digits += c;  // leading zeros are not significant
    if (digits.size() > 6) return false;
  }
  return true;
}

void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

}  // namespace

TEST_CASE("lgi bifurcation: class changes located and branches named", "[atlas][cli]") {
  const std::string dir = testing::scratch_dir("atlas_cli_bif");
  const auto r = testing::run_lgi("bifurcation --scene " + scenes + "/gyroscope.toml --out " + dir + "/g.h5");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Contains(" class_change"));
  CHECK(six_digits(r.out));
  const std::string csv = testing::read_text(dir + "/g.csv");
  CHECK_THAT(csv.substr(0, csv.find('\n')), Contains("class_change"));
}

TEST_CASE("lgi region echoes l and h with 6 digits", "[atlas][cli]") {
  const std::string dir = testing::scratch_dir("atlas_cli_region");
  const auto r = testing::run_lgi("region --scene " + scenes + "/general_top_richter.toml --l 2.2 --h 3 --grid 40 --out " +
                                  dir + "/r.h5");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Contains("region: l = 2.2, h = 3:"));
  CHECK(six_digits(r.out));
}

TEST_CASE("lgi region on the Kovalevskaya top at l = 2: a degenerate point, not an unresolved grid", "[atlas][cli]") {
  const std::string dir = testing::scratch_dir("atlas_cli_kov");
  const auto r = testing::run_lgi("region --scene " + scenes + "/kovalevskaya.toml --l 2 --h 2.5 --out " + dir + "/k.h5");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Contains("degenerate critical point"));
  CHECK_THAT(r.out, !Contains("not resolved"));
}

TEST_CASE("lgi poincare --seeds: orbits from section points and states, and the refusals", "[atlas][cli][poincare]") {
  const std::string dir = testing::scratch_dir("atlas_cli_seeds");
  const std::string base = "poincare --scene " + scenes + "/kovalevskaya.toml --l 1 --h 2 --t-end 20 --threads 1 ";
  write(dir + "/points.csv", "# phi, theta, sheet on Richter's section\nphi,theta,sheet\n0.5,1.2,1\n2.0,2.0,-1\n");
  const auto ok = testing::run_lgi(base + "--seeds " + dir + "/points.csv --out " + dir + "/p.h5");
  INFO(ok.err);
  REQUIRE(ok.status == 0);
  CHECK_THAT(ok.out, Contains("poincare: 2 orbits") && Contains("at l = 1, h = 2 ("));
  // A state on the level: Gamma = e3, Pi = (Pi1, 0, 1) with H = Pi1^2/4 + 1/2 = 2 (J = (2, 2, 1), chi = e1).
  write(dir + "/states.csv", "gamma_1,gamma_2,gamma_3,angular_momentum_1,angular_momentum_2,angular_momentum_3\n"
                             "0,0,1,2.4494897427831781,0,1\n");
  const auto state = testing::run_lgi(base + "--seeds " + dir + "/states.csv --out " + dir + "/s.h5");
  INFO(state.err);
  CHECK(state.status == 0);
  CHECK_THAT(state.out, Contains("poincare: 1 orbits"));
  const auto refused = [&](const std::string& args, const std::string& what) {
    const auto r = testing::run_lgi(args + " --out " + dir + "/x.h5 --force");
    INFO(args << "\n" << r.err);
    CHECK(r.status == 2);
    CHECK(testing::line_count(r.err) == 1);
    CHECK_THAT(r.err, Contains(what));
  };
  write(dir + "/bad.csv", "x,y\n1,2\n");
  refused(base + "--seeds " + dir + "/bad.csv", "--seeds: " + dir + "/bad.csv line 1");
  write(dir + "/off.csv", "gamma_1,gamma_2,gamma_3,angular_momentum_1,angular_momentum_2,angular_momentum_3\n"
                          "0,0,1,0,0,1\n");
  refused(base + "--seeds " + dir + "/off.csv", "not on the level");
  write(dir + "/outside.csv", "phi,theta,sheet\n0,0.3,1\n");  // Gamma near +e1, where U_l > h = -0.5
  refused("poincare --scene " + scenes + "/kovalevskaya.toml --l 1 --h -0.5 --t-end 20 --seeds " + dir +
              "/outside.csv",
          "outside the accessible region");
  refused(base + "--ics 3 --seeds " + dir + "/points.csv", "--ics: not with --seeds");
  refused("poincare --scene " + scenes + "/cardan_euler_symmetric_up.toml --l 2.85 --h 6.96 --t-end 1 --seeds " + dir +
              "/points.csv",
          "--seeds: not for a Cardan top");
}

TEST_CASE("a tilted Cardan frame: no p1 error reported, --l only sets the initial p1", "[atlas][cli][cardan]") {
  const std::string dir = testing::scratch_dir("atlas_cli_cardan");
  const auto up = testing::run_lgi("simulate --scene " + scenes + "/cardan_lagrange_upright.toml --scheme cardan-rk4 "
                                   "--t-end 0.01 --out " + dir + "/u.h5");
  REQUIRE(up.status == 0);
  CHECK_THAT(up.out, Contains("cardan_momentum_1_error_max="));
  const auto tilted = testing::run_lgi("simulate --scene " + scenes + "/cardan_lagrange_horizontal.toml --scheme "
                                       "cardan-rk4 --t-end 0.01 --out " + dir + "/h.h5");
  INFO(tilted.err);
  REQUIRE(tilted.status == 0);
  CHECK_THAT(tilted.out, Contains("cardan_momentum_1_conserved=no") && !Contains("cardan_momentum_1_error"));
  const auto section = testing::run_lgi("poincare --scene " + scenes + "/cardan_lagrange_horizontal.toml --l 10 "
                                        "--h 204 --ics 1 --t-end 0.05 --dt 0.001 --out " + dir + "/p.h5");
  INFO(section.err);
  CHECK(section.status == 0);
  CHECK(testing::line_count(section.err) == 1);
  CHECK_THAT(section.err, Contains("warning: --l: p1 is no integral"));
  CHECK_THAT(section.out, Contains("at initial p1 = 10, h = 204,"));
}

}  // namespace test_atlas_cli

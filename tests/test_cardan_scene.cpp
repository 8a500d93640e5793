// Scene files with a [suspension] table (docs/cardan.md §6): what they
// parse to, the bad input that gets one line naming the key (exit 2), and
// `lgi simulate` on a shipped Cardan scene (the H5MD file and the exit
// statuses of a scheme on the wrong kind of scene).
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "experiments/io/scene_suspension.hpp"
#include "support/run_command.hpp"
#include "support/scene_error.hpp"

namespace test_cardan_scene {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using Catch::Matchers::Contains;

namespace {

std::string cardan_scene(const std::string& suspension, const std::string& initial = "",
                         const std::string& body_extra = "center_of_mass = [0.0, 0.0, 1.0]\n") {
  return "name = \"c\"\n[body]\nmass = 5.0\ninertia_cm = [0.8, 0.8, 1.0]\n" + body_extra +
         "[gravity]\ng = 9.81\n[suspension]\n" + suspension + "[initial]\n" +
         (initial.empty() ? "cardan_angles = [0.0, 0.5, 0.0]\ncardan_rates = [0.0, 0.0, 10.0]\n" : initial);
}
const std::string good = "tilt = 0.3\nouter_inertia = 0.2\ninner_inertia = [0.1, 0.2, 0.1]\n";

}  // namespace

TEST_CASE("a [suspension] scene parses to the Cardan state and the body's (R, Pi)", "[cardan][scene]") {
  const system::Scene s = experiments::parse_scene(cardan_scene(good), "test.toml");
  REQUIRE(s.suspension);
  CHECK(s.suspension->tilt == 0.3);
  CHECK(s.suspension->inner_inertia == lie::Vec3(0.1, 0.2, 0.1));
  const system::CardanTop top = experiments::cardan_top(s);
  CHECK(s.cardan_initial.q == lie::Vec3(0.0, 0.5, 0.0));
  CHECK((top.velocity(s.cardan_initial) - lie::Vec3(0.0, 0.0, 10.0)).norm() <= 1e-13);
  CHECK((s.initial.R - top.attitude(s.cardan_initial.q)).norm() == 0.0);
}

TEST_CASE("bad [suspension] input: one line naming the key", "[cardan][scene]") {
  CHECK_THAT(testing::error_of(cardan_scene("tilt = 3.5\nouter_inertia = 0.2\ninner_inertia = [0.1, 0.2, 0.1]\n")),
             Contains("[suspension] tilt: must be in [0, pi]"));
  CHECK_THAT(testing::error_of(cardan_scene("tilt = -0.1\nouter_inertia = 0.2\ninner_inertia = [0.1, 0.2, 0.1]\n")),
             Contains("[suspension] tilt"));
  CHECK_THAT(testing::error_of(cardan_scene("tilt = 0.3\nouter_inertia = -0.2\ninner_inertia = [0.1, 0.2, 0.1]\n")),
             Contains("[suspension] outer_inertia: must be >= 0"));
  CHECK_THAT(testing::error_of(cardan_scene("tilt = 0.3\nouter_inertia = 0.2\ninner_inertia = [0.1, -0.2, 0.1]\n")),
             Contains("[suspension] inner_inertia: moment 2 must be >= 0"));
  CHECK_THAT(testing::error_of(cardan_scene(good + "inner_mass = -1.0\n")), Contains("[suspension] inner_mass"));
  CHECK_THAT(testing::error_of(cardan_scene(good + "tilted = 1.0\n")), Contains("[suspension] tilted: unknown key"));
  CHECK_THAT(testing::error_of(cardan_scene("outer_inertia = 0.2\ninner_inertia = [0.1, 0.2, 0.1]\n")),
             Contains("[suspension] tilt: missing"));
  // A free body (no centre of mass, no gravity) in a suspension.
  CHECK_THAT(testing::error_of("name = \"c\"\n[body]\ninertia = [1.0, 2.0, 2.5]\n[suspension]\n" + good +
                               "[initial]\ncardan_angles = [0.0, 0.5, 0.0]\ncardan_rates = [0.0, 0.0, 1.0]\n"),
             Contains("[suspension]") && Contains("free body") && Contains("center_of_mass"));
  CHECK_THAT(testing::error_of(cardan_scene(good, "euler_zxz = [0.0, 0.5, 0.0]\ncardan_rates = [0.0, 0.0, 1.0]\n")),
             Contains("[initial] euler_zxz"));
  CHECK_THAT(testing::error_of(cardan_scene(good, "cardan_angles = [0.0, 0.5, 0.0]\n")),
             Contains("[initial] cardan_rates: missing"));
  CHECK_THAT(testing::error_of(cardan_scene("tilt = 0.0\nouter_inertia = 0.0\ninner_inertia = [0.0, 0.0, 0.0]\n",
                                            "cardan_angles = [0.0, 0.0, 0.0]\ncardan_rates = [0.0, 0.0, 1.0]\n")),
             Contains("[initial] cardan_angles") && Contains("gimbal lock"));
  CHECK_THAT(testing::error_of("name = \"c\"\n[body]\ninertia = [1.0, 2.0, 2.5]\n[initial]\n"
                               "cardan_angles = [0.0, 0.5, 0.0]\n"),
             Contains("[initial] cardan_angles: needs a [suspension] table"));
}

TEST_CASE("lgi simulate on a Cardan scene: H5MD output and the wrong scheme kinds", "[cardan][cli]") {
  const std::string dir = testing::scratch_dir("cardan_cli");
  const std::string scenes = LGI_SCENES_DIR;
  const testing::CommandResult ok =
      testing::run_lgi("simulate --scene " + scenes + "/cardan_lagrange_upright.toml --scheme cardan-midpoint " +
                       "--t-end 0.1 --out " + dir + "/c.h5");
  INFO(ok.err);
  CHECK(ok.status == 0);
  CHECK_THAT(ok.out, Contains("scheme=cardan-midpoint steps=100") && Contains("cardan_momentum_1_error_max="));
  const testing::CommandResult dump = testing::run_lgi("simulate --scene " + scenes +
                                                       "/cardan_lagrange_upright.toml --scheme rkmk4 --t-end 0.1 "
                                                       "--out " + dir + "/d.h5");
  CHECK(dump.status == 2);  // a scheme of the other state space is bad input
  CHECK_THAT(dump.err, Contains("rkmk4") && Contains("SO(3) x R^3") && Contains("T^3 x R^3"));
  const testing::CommandResult wrong = testing::run_lgi(
      "simulate --scene " + scenes + "/heavy_top_trindade_1.toml --scheme cardan-rk4 --t-end 0.1 --out " + dir + "/e.h5");
  CHECK(wrong.status == 2);
  CHECK_THAT(wrong.err, Contains("cardan-rk4") && Contains("[suspension]") && Contains("SO(3) x R^3"));
  const testing::CommandResult bad = testing::run_lgi("simulate --scene " + scenes +
                                                      "/cardan_lagrange_upright.toml --scheme cardan-dp54 --tol -1 "
                                                      "--out " + dir + "/f.h5");
  CHECK(bad.status == 2);
  CHECK(testing::line_count(bad.err) == 1);
}

}  // namespace test_cardan_scene

// What a newcomer meets first, through the lgi command as a user runs it:
// the facts `lgi schemes` states, the CPU times `simulate` reports, the
// conditioning floor of an exact reference, one rule for run settings in
// every subcommand, and error messages that point at the fix.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "support/h5_read.hpp"
#include "support/run_command.hpp"

namespace test_first_use {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi::testing;
namespace fs = std::filesystem;

namespace {
const std::string scenes = LGI_SCENES_DIR;

/// The JSON object of one scheme in `lgi schemes --json` (one object a line).
std::string json_entry(const std::string& json, const std::string& name) {
  for (const auto& line : split_lines(json))
    if (line.find("{\"name\": \"" + name + "\"") != std::string::npos) return line;
  return {};
}

/// A free body with no [run] table at all: every setting comes from the command line.
std::string scene_without_run(const std::string& dir) {
  const std::string path = dir + "/no_run.toml";
  std::ofstream(path) << "name = \"no run table\"\n[body]\ninertia = [1.0, 2.0, 3.0]\n"
                         "[initial]\nangular_velocity = [0.1, 1.0, 0.2]\n";
  return path;
}

/// A T-handle spun about its intermediate axis with a 1e-3 perturbation: the
/// exact flow is ill-conditioned near the separatrix.
std::string t_handle(const std::string& dir) {
  const std::string path = dir + "/t_handle.toml";
  std::ofstream(path) << "name = \"T-handle\"\n[body]\ninertia = [1.0, 2.0, 3.0]\n"
                         "[initial]\nangular_velocity = [1.0e-3, 5.0, 1.0e-3]\n[run]\nt_end = 50.0\ndt = 1.0e-2\n";
  return path;
}
}  // namespace

TEST_CASE("lgi schemes states order 2 with torque for preprocessed DMV, and kind and base", "[cli][schemes]") {
  const auto j = run_lgi("schemes --json");
  REQUIRE(j.status == 0);
  for (const char* name : {"dmv-pre4", "dmv-pre6", "dmv-pre8", "dmv-pre10"}) {
    const std::string e = json_entry(j.out, name);
    INFO(e);
    CHECK(e.find("\"order_with_torque\": 2") != std::string::npos);
    CHECK(e.find("\"kind\": \"lie-group\"") != std::string::npos);
  }
  const std::string comp = json_entry(j.out, "lgvi@kahan-li8");
  CHECK(comp.find("\"kind\": \"composition\", \"base\": \"lgvi\"") != std::string::npos);
  CHECK(json_entry(j.out, "quat/rk4").find("\"kind\": \"baseline\", \"base\": null") != std::string::npos);
  CHECK(json_entry(j.out, "exact").find("\"kind\": \"exact\"") != std::string::npos);

  const auto table = run_lgi("schemes");
  REQUIRE(table.status == 0);
  CHECK(table.out.find("order a/b: a on free bodies, b on scenes with torques") != std::string::npos);
  bool split_order_row = false;
  for (const auto& line : split_lines(table.out)) {
    INFO(line);
    CHECK(line.size() <= 120);  // the compact view: no reference, no notes
    if (line.rfind("dmv-pre4 ", 0) == 0) split_order_row = line.find(" 4/2 ") != std::string::npos;
  }
  CHECK(split_order_row);  // the legend's a/b format is used
  CHECK(run_lgi("schemes --long").out.find("Hairer & Vilmart") != std::string::npos);
}

TEST_CASE("lgi schemes --scene and --family filter the listing", "[cli][schemes]") {
  const auto kova = run_lgi("schemes --scene " + scenes + "/kovalevskaya.toml");
  REQUIRE(kova.status == 0);
  std::string pre4, exact;
  for (const auto& line : split_lines(kova.out)) {
    if (line.rfind("dmv-pre4 ", 0) == 0) pre4 = line;
    if (line.rfind("exact ", 0) == 0) exact = line;
  }
  CHECK(std::regex_search(pre4, std::regex("^dmv-pre4 +2 ")));  // its order on a top
  CHECK(exact.empty());                                          // free bodies only
  const auto free = run_lgi("schemes --scene " + scenes + "/free_body_hlw.toml --json");
  CHECK(json_entry(free.out, "dmv-pre4").find("\"order_on_scene\": 4") != std::string::npos);

  const auto comps = run_lgi("schemes --family composition --json");
  REQUIRE(comps.status == 0);
  int n = 0;
  for (const auto& line : split_lines(comps.out))
    if (line.find("\"name\"") != std::string::npos) {
      ++n;
      CHECK(line.find("\"kind\": \"composition\"") != std::string::npos);
    }
  CHECK(n >= 20);
  const auto none = run_lgi("schemes --family nonsense");
  CHECK(none.status == 2);
  CHECK(none.err.find("--family") != std::string::npos);
}

TEST_CASE("simulate reports stepping and output CPU time apart, and formatted", "[cli][cpu]") {
  const std::string dir = scratch_dir("first_use_cpu");
  const std::string out = dir + "/a.h5";
  const auto r = run_lgi("simulate --scene " + scenes + "/free_body_hlw.toml --scheme rkmk4 --dt 1e-3 --t-end 2 --out " + out);
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  const std::regex sci("[0-9]\\.[0-9]{3}e[-+][0-9]+");
  std::smatch m;
  REQUIRE(std::regex_search(r.out, m, std::regex("cpu_seconds=(\\S+) output_seconds=(\\S+)")));
  CHECK(std::regex_match(m[1].str(), sci));
  CHECK(std::regex_match(m[2].str(), sci));
  // Both times are stored (no timed assertion: speed is a benchmark's business).
  const double stepping = read_double_attribute(out, "/diagnostics", "cpu_seconds");
  const double output = read_double_attribute(out, "/diagnostics", "output_seconds");
  CHECK(stepping > 0.0);
  CHECK(output > 0.0);
  // The invariant errors: at t_end and the largest over the samples, labelled.
  CHECK(std::regex_search(r.out, std::regex("energy_error_end=\\S+ energy_error_max=\\S+")));
  CHECK(r.out.find("0000000000") == std::string::npos);  // no 17-digit round-off

  const auto big = run_lgi("simulate --scene " + scenes + "/free_body_hlw.toml --scheme lie-euler --dt 1e-6 --t-end 0 "
                           "--out " + dir + "/b.h5");
  CHECK(big.err.find("warning") == std::string::npos);  // no step, no warning
  const auto large = run_lgi("simulate --scene " + scenes + "/free_body_hlw.toml --scheme lie-euler --dt 1e-7 "
                             "--t-end 0.1 --save-every 1 --out " + dir + "/c.h5");
  CHECK(large.status == 0);
  CHECK(large.err.find("warning: --save-every 1 writes") != std::string::npos);
}

TEST_CASE("an exact reference has a conditioning floor: rows below it are marked", "[cli][work-precision]") {
  const std::string dir = scratch_dir("first_use_floor");
  const std::string out = dir + "/wp.h5";
  const auto r = run_lgi("work-precision --scene " + t_handle(dir) +
                         " --schemes rkmk4 --dt 0.02,0.01,0.005,0.0025 --repeat 1 --out " + out);
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  CHECK(read_string_attribute(out, "/reference", "kind") == "exact");
  const double floor = read_double_attribute(out, "/reference", "estimated_error");
  CHECK(floor > 1e-10);  // about 1e-7 on this separatrix
  const auto below = read_dataset(out, "/results/below_reference_floor").data;
  const auto error = read_dataset(out, "/results/error").data;
  REQUIRE(below.size() == 4);
  CHECK(below.back() == 1.0);  // rkmk4 at h = 0.0025 is under the floor, not "order 1.5"
  CHECK(std::isnan(error.back()));
}

TEST_CASE("run settings: the command line, then the scene's [run], in every subcommand", "[cli][settings]") {
  const std::string dir = scratch_dir("first_use_settings");
  const std::string book = scenes + "/dzhanibekov_book_axis2.toml";
  SECTION("long-time takes dt and t_end from the scene") {
    const auto r = run_lgi("long-time --scene " + book + " --scheme rkmk4 --out " + dir + "/lt.h5");
    INFO(r.out << r.err);
    CHECK(r.status == 0);
    CHECK(read_double_attribute(dir + "/lt.h5", "/parameters", "dt") > 0.0);
    CHECK(r.out.find("wrote " + dir + "/lt.h5 and " + dir + "/lt.csv") != std::string::npos);
  }
  SECTION("a scene without [run] runs when the flags are given, and names the missing flag otherwise") {
    const std::string scene = scene_without_run(dir);
    CHECK(run_lgi("simulate --scene " + scene + " --scheme rkmk4 --dt 0.01 --t-end 1 --out " + dir + "/s.h5").status ==
          0);
    const auto missing = run_lgi("simulate --scene " + scene + " --scheme rkmk4 --dt 0.01 --out " + dir + "/t.h5");
    CHECK(missing.status == 2);
    CHECK(line_count(missing.err) == 1);
    CHECK(missing.err.find("--t-end") != std::string::npos);
    CHECK(run_lgi("work-precision --scene " + scene + " --schemes rkmk4 --dt 0.1,0.05 --t-end 1 --repeat 1 --out " +
                  dir + "/w.h5")
              .status == 0);
    CHECK(run_lgi("long-time --scene " + scene + " --scheme rkmk4 --dt 0.01 --t-end 1 --out " + dir + "/l.h5")
              .status == 0);
  }
  SECTION("work-precision takes its steps from the scene's dt") {
    const auto r = run_lgi("work-precision --scene " + book + " --schemes rkmk4 --t-end 1 --repeat 1 --out " + dir +
                           "/wp.h5");
    INFO(r.out << r.err);
    CHECK(r.status == 0);
    CHECK(read_dataset(dir + "/wp.h5", "/results/dt").data.size() == 4);
  }
  SECTION("--help shows the list syntax that works") {
    const auto help = run_lgi("work-precision --help");
    CHECK(help.out.find("--schemes A,B,...") != std::string::npos);
    CHECK(help.out.find("--dt H1,H2,...") != std::string::npos);
    CHECK(help.out.find("TEXT ...") == std::string::npos);
    for (const char* sub : {"work-precision", "long-time", "stress", "singularity"}) {
      INFO(sub);
      CHECK(run_lgi(std::string(sub) + " --help").out.find("(out.h5 -> out.csv)") != std::string::npos);
    }
  }
}

TEST_CASE("error messages point at the fix", "[cli][bad-input]") {
  const std::string dir = scratch_dir("first_use_messages");
  const std::string book = scenes + "/dzhanibekov_book_axis2.toml";
  const auto tol = run_lgi("simulate --scene " + book + " --scheme rkmk4 --dt 1e-3 --tol 1e-6 --out " + dir + "/a.h5");
  CHECK(tol.status == 2);
  CHECK(tol.err.find("give --dt") == std::string::npos);  // --dt was given
  CHECK(tol.err.find("drop --tol") != std::string::npos);
  const auto rk4 = run_lgi("simulate --scene " + book + " --scheme rk4 --dt 1e-3 --out " + dir + "/b.h5");
  CHECK(rk4.status == 2);
  CHECK(line_count(rk4.err) == 1);
  CHECK(rk4.err.find("did you mean") != std::string::npos);
  CHECK(rk4.err.find("quat/rk4") != std::string::npos);
  CHECK(rk4.err.find("rkmk4") != std::string::npos);
  const auto list = run_lgi("work-precision --scene " + book + " --schemes rkmk4,lgiv --dt 0.1 --out " + dir + "/c.h5");
  CHECK(list.status == 2);
  CHECK(list.err.find("did you mean lgvi") != std::string::npos);
}

}  // namespace test_first_use

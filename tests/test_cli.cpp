// The lgi command as a user runs it: exit statuses and one-line errors
// (README.md, "Using lgi"), no output file on bad input, and the trajectory of `simulate`.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/h5_read.hpp"
#include "support/run_command.hpp"

namespace test_cli {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi::testing;
namespace fs = std::filesystem;

namespace {
const std::string scenes = LGI_SCENES_DIR;
const std::string book2 = scenes + "/dzhanibekov_book_axis2.toml";
const std::string top1 = scenes + "/heavy_top_trindade_1.toml";

void require_bad_input(const CommandResult& r, const std::string& names, const std::string& out_file) {
  INFO("stderr: " << r.err);
  CHECK(r.status == 2);
  CHECK(line_count(r.err) == 1);
  CHECK(r.err.find(names) != std::string::npos);
  CHECK_FALSE(fs::exists(out_file));
  CHECK_FALSE(fs::exists(out_file + ".partial"));
}
}  // namespace

TEST_CASE("bad flags give exit 2, one line naming the flag, and no output file", "[cli][bad-input]") {
  const std::string dir = scratch_dir("cli_bad_flags");
  const std::string out = dir + "/a.h5";
  // `simulate` on book axis 2 with these flags (then --out): the flag the one line must name.
  struct BadFlags {
    const char* what;
    std::string flags;
    const char* named;
  };
  const std::vector<BadFlags> rows = {
      {"unknown scheme", "--scheme rk17 --dt 1e-3", "--scheme"},
      {"dt = 0", "--scheme rkmk4 --dt 0", "--dt"},
      {"dt < 0", "--scheme rkmk4 --dt -1e-3", "--dt"},
      {"dt not a number", "--scheme rkmk4 --dt abc", "--dt"},
      {"tol <= 0", "--scheme rkmk-dp54 --tol 0", "--tol"},
      {"tol given to a fixed-step scheme", "--scheme rkmk4 --tol 1e-6", "--tol"},
      {"negative t-end", "--scheme rkmk4 --t-end -1", "--t-end"},
      {"save-every 0", "--scheme rkmk4 --save-every 0", "--save-every"},
      {"unknown flag", "--scheme rkmk4 --dtt 1", "--dtt"},
  };
  for (const auto& row : rows) {
    DYNAMIC_SECTION(row.what) {
      require_bad_input(run_lgi("simulate --scene " + book2 + " " + row.flags + " --out " + out), row.named, out);
    }
  }
  SECTION("missing required flag") {
    require_bad_input(run_lgi("simulate --scene " + book2 + " --scheme rkmk4"), "--out", out);
  }
  SECTION("missing scene file") {
    require_bad_input(run_lgi("simulate --scene " + dir + "/nope.toml --scheme rkmk4 --out " + out), "nope.toml", out);
  }
  SECTION("unwritable output") {
    const std::string bad = dir + "/no/such/dir/a.h5";
    require_bad_input(run_lgi("simulate --scene " + book2 + " --scheme rkmk4 --out " + bad), bad, bad);
  }
  SECTION("bad scene file: the message names file and key") {
    const std::string scene = dir + "/typo.toml";
    std::ofstream(scene) << "name = \"typo\"\n[body]\ninertia = [1, 2, 2.5]\nmas = 3\n[run]\nt_end = 1\ndt = 0.1\n";
    const auto r = run_lgi("simulate --scene " + scene + " --scheme rkmk4 --out " + out);
    require_bad_input(r, "typo.toml", out);
    CHECK(r.err.find("mas") != std::string::npos);
  }
}

TEST_CASE("an existing output is kept unless --force", "[cli]") {
  const std::string dir = scratch_dir("cli_force");
  const std::string out = dir + "/a.h5";
  const std::string args = "simulate --scene " + book2 + " --scheme rkmk4 --dt 1e-2 --t-end 0.5 --out " + out;
  REQUIRE(run_lgi(args).status == 0);
  const auto first = fs::last_write_time(out);
  const auto again = run_lgi(args);
  CHECK(again.status == 2);
  CHECK(again.err.find(out) != std::string::npos);
  CHECK(fs::last_write_time(out) == first);
  CHECK(run_lgi(args + " --force").status == 0);
  CHECK_FALSE(fs::exists(out + ".partial"));
}

TEST_CASE("a scheme applied to a scene it cannot handle exits 1 without a file", "[cli]") {
  const std::string dir = scratch_dir("cli_unsupported");
  const std::string out = dir + "/a.h5";
  const auto r = run_lgi("simulate --scene " + top1 + " --scheme exact --dt 1e-3 --out " + out);
  INFO(r.err);
  CHECK(r.status == 2);  // a scheme that does not apply to the scene: bad input (README)
  CHECK(line_count(r.err) == 1);
  CHECK(r.err.find("free body") != std::string::npos);
  CHECK_FALSE(fs::exists(out));
  CHECK_FALSE(fs::exists(out + ".partial"));
}

TEST_CASE("degenerate runs: t_end = 0 and dt > t_end", "[cli]") {
  const std::string dir = scratch_dir("cli_degenerate");
  const auto zero = run_lgi("simulate --scene " + book2 + " --scheme rkmk4 --t-end 0 --out " + dir + "/z.h5");
  CHECK(zero.status == 0);
  CHECK(read_dataset(dir + "/z.h5", "/particles/body/orientation/time").data == std::vector<double>{0.0});
  const auto big = run_lgi("simulate --scene " + book2 + " --scheme rkmk4 --dt 5 --t-end 0.5 --out " + dir + "/b.h5");
  CHECK(big.status == 0);
  CHECK(read_dataset(dir + "/b.h5", "/particles/body/orientation/time").data == std::vector<double>{0.0, 0.5});
}

TEST_CASE("lgi schemes and lgi scenes list the registry and the shipped scenes", "[cli]") {
  const auto s = run_lgi("schemes");
  CHECK(s.status == 0);
  for (const char* name : {"exact", "lie-euler", "rkmk2", "rkmk3", "rkmk4", "rkmk-dp54", "cg3", "cg4a", "cf4"})
    CHECK(s.out.find(name) != std::string::npos);
  const auto j = run_lgi("schemes --json");
  CHECK(j.status == 0);
  CHECK(j.out.find("\"name\": \"rkmk4\", \"order\": 4") != std::string::npos);
  const auto sc = run_lgi("scenes " + scenes);
  CHECK(sc.status == 0);
  CHECK(line_count(sc.out) == 26);
  CHECK(sc.out.find("kovalevskaya.toml") != std::string::npos);
  CHECK(sc.out.find("kovalevskaya_k") != std::string::npos);
}

}  // namespace test_cli

// lgi stress (experiments/STRESS.md): the quick suite through the command
// line, its files, and the pass criteria it computes.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "integrators/registry/registry.hpp"
#include "support/h5_read.hpp"
#include "support/run_command.hpp"

namespace test_stress {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi::testing;
namespace fs = std::filesystem;

namespace {

const std::vector<std::string> all_cases = {"large-steps", "separatrix", "theta-pi",  "fast-top",  "needle",
                                            "flat-plate",  "near-sphere", "stiffness", "units",     "degenerate"};

struct Table {
  std::vector<std::string> case_id, variant, scheme, outcome, reason;
  std::vector<double> pass, error, max_invariant_error, steps, cpu_seconds;
  std::size_t size() const { return scheme.size(); }
};

Table read_results(const std::string& file) {
  Table t;
  t.case_id = read_string_dataset(file, "/results/case");
  t.variant = read_string_dataset(file, "/results/variant");
  t.scheme = read_string_dataset(file, "/results/scheme");
  t.outcome = read_string_dataset(file, "/results/outcome");
  t.reason = read_string_dataset(file, "/results/reason");
  t.pass = read_dataset(file, "/results/pass").data;
  t.error = read_dataset(file, "/results/error").data;
  t.max_invariant_error = read_dataset(file, "/results/max_invariant_error").data;
  t.steps = read_dataset(file, "/results/steps").data;
  t.cpu_seconds = read_dataset(file, "/results/cpu_seconds").data;
  return t;
}

/// Explicit schemes of the registry: neither implicit nor a coordinate baseline.
std::set<std::string> explicit_schemes() {
  std::set<std::string> names;
  for (const auto& s : lgi::integrators::scheme_registry())
    if (!s.properties.implicit && !s.properties.baseline) names.insert(s.name);
  return names;
}

std::string row_text(const Table& t, std::size_t i) {
  return t.case_id[i] + " / " + t.variant[i] + " / " + t.scheme[i] + ": " + t.outcome[i] + " (" + t.reason[i] +
         ") error " + std::to_string(t.error[i]) + " pass " + std::to_string(static_cast<int>(t.pass[i]));
}

}  // namespace

TEST_CASE("lgi stress --quick runs every case against every scheme and writes HDF5 and CSV", "[stress]") {
  const std::string dir = scratch_dir("stress_quick");
  const std::string out = dir + "/stress.h5";
  const std::string csv = dir + "/stress.csv";
  const auto r = run_lgi("stress --quick --out " + out, dir);
  {
    INFO("stderr: " << r.err);
    INFO("stdout: " << r.out);
    REQUIRE(r.status == 0);
  }
  REQUIRE(fs::exists(out));
  REQUIRE(fs::exists(csv));
  CHECK_FALSE(fs::exists(out + ".partial"));
  CHECK_FALSE(fs::exists(csv + ".partial"));

  const Table t = read_results(out);
  REQUIRE(t.size() > 0);
  REQUIRE(t.case_id.size() == t.size());
  REQUIRE(t.pass.size() == t.size());
  REQUIRE(t.error.size() == t.size());

  // The CSV holds the same table: a header and one line per row (reasons may
  // contain commas, but never line breaks).
  CHECK(line_count(read_text(csv)) == static_cast<int>(t.size()) + 1);
  CHECK(read_text(csv).rfind("case,variant,scheme,outcome,reason,pass,error", 0) == 0);

  // Provenance.
  CHECK(read_string_attribute(out, "/parameters", "command_line").find("stress --quick") != std::string::npos);
  CHECK_FALSE(read_string_attribute(out, "/parameters", "compiler").empty());
  CHECK(read_string_attribute(out, "/diagnostics", "status") == "ok");

  // Every case is present, with every registered scheme in each of its variants.
  std::set<std::string> cases(t.case_id.begin(), t.case_id.end());
  for (const auto& c : all_cases) {
    INFO("case " << c);
    CHECK(cases.count(c) == 1);
    CHECK(r.out.find(c) != std::string::npos);  // the summary names it
  }
  CHECK(r.out.find("total") != std::string::npos);
  const std::size_t n_schemes = lgi::integrators::scheme_registry().size();
  std::map<std::string, std::set<std::string>> schemes_per_variant;
  for (std::size_t i = 0; i < t.size(); ++i) schemes_per_variant[t.case_id[i] + "/" + t.variant[i]].insert(t.scheme[i]);
  for (const auto& [variant, schemes] : schemes_per_variant) {
    INFO("variant " << variant);
    CHECK(schemes.size() == n_schemes);
  }

  // Every row has a valid outcome; refused and failed rows say why; pass is 0 or 1.
  for (std::size_t i = 0; i < t.size(); ++i) {
    INFO(row_text(t, i));
    const std::string& o = t.outcome[i];
    CHECK((o == "ok" || o == "refused" || o == "failed"));
    if (o != "ok") CHECK_FALSE(t.reason[i].empty());
    CHECK((t.pass[i] == 0.0 || t.pass[i] == 1.0));
    CHECK(t.cpu_seconds[i] >= 0.0);
    // Never a silent wrong answer marked as a pass.
    if (o == "ok" && t.pass[i] == 1.0) {
      CHECK(std::isfinite(t.error[i]));
      CHECK(std::isfinite(t.max_invariant_error[i]));
      CHECK(t.error[i] <= 1e-2);
    }
  }

  // The degenerate and units cases pass for the explicit schemes.
  const std::set<std::string> explicit_names = explicit_schemes();
  REQUIRE(explicit_names.count("rkmk4") == 1);
  int checked = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t.case_id[i] != "degenerate" && t.case_id[i] != "units") continue;
    if (!explicit_names.count(t.scheme[i])) continue;
    INFO(row_text(t, i));
    CHECK(t.pass[i] == 1.0);
    ++checked;
  }
  CHECK(checked > 0);

  // The units case compares like with like: an ok row agrees to 1e-10.
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t.case_id[i] == "units" && t.scheme[i] == "rkmk4") {
      INFO(row_text(t, i));
      CHECK(t.outcome[i] == "ok");
      CHECK(t.error[i] <= 1e-10);
    }
  // t_end = 0: no step, and the initial state: bit for bit from a Lie-group scheme (the
  // state is never touched), to round-off from a baseline (a chart round trip).
  std::set<std::string> baselines;
  for (const auto& s : lgi::integrators::scheme_registry())
    if (s.properties.baseline) baselines.insert(s.name);
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t.case_id[i] == "degenerate" && t.variant[i].find("t_end=0") != std::string::npos && t.outcome[i] == "ok") {
      INFO(row_text(t, i));
      CHECK(t.steps[i] == 0.0);
      if (baselines.count(t.scheme[i])) CHECK(t.error[i] <= 1e-15);
      else CHECK(t.error[i] == 0.0);
    }

  // Large steps past pi: no ok row with a huge error is marked pass, and the
  // Cayley-based schemes refuse rather than alias the rotation.
  int past_pi = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t.case_id[i] != "large-steps" || t.variant[i].find("h|Omega|=4") == std::string::npos) continue;
    ++past_pi;
    INFO(row_text(t, i));
    if (t.outcome[i] == "ok" && !(t.error[i] <= 1e-2)) CHECK(t.pass[i] == 0.0);
    if (t.scheme[i] == "dmv" && t.variant[i].rfind("book", 0) == 0) CHECK(t.outcome[i] == "refused");
    if (t.scheme[i] == "simo-wong") CHECK(t.outcome[i] == "refused");
  }
  CHECK(past_pi > 0);

  // The exact flow is its own reference on the free bodies.
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t.scheme[i] == "exact" && (t.case_id[i] == "needle" || t.case_id[i] == "flat-plate" ||
                                   t.case_id[i] == "near-sphere")) {
      INFO(row_text(t, i));
      CHECK(t.outcome[i] == "ok");
      CHECK(t.error[i] <= 1e-9);
    }

  // Every variant's set-up is recorded.
  CHECK_FALSE(read_string_attribute(out, "/case_00", "criterion").empty());
  CHECK_FALSE(read_string_attribute(out, "/case_00", "description").empty());
}

TEST_CASE("lgi stress --schemes restricts the suite; bad flags give exit 2 and no file", "[stress][bad-input]") {
  const std::string dir = scratch_dir("stress_flags");
  const std::string out = dir + "/s.h5";
  const std::string csv = dir + "/s.csv";
  auto no_files = [&] {
    CHECK_FALSE(fs::exists(out));
    CHECK_FALSE(fs::exists(csv));
    CHECK_FALSE(fs::exists(out + ".partial"));
    CHECK_FALSE(fs::exists(csv + ".partial"));
  };
  SECTION("unknown scheme in --schemes") {
    const auto r = run_lgi("stress --quick --schemes rkmk4,rk17 --out " + out, dir);
    INFO("stderr: " << r.err);
    CHECK(r.status == 2);
    CHECK(line_count(r.err) == 1);
    CHECK(r.err.find("--schemes") != std::string::npos);
    CHECK(r.err.find("rk17") != std::string::npos);
    no_files();
  }
  SECTION("empty name in --schemes") {
    const auto r = run_lgi("stress --quick --schemes rkmk4,,cg3 --out " + out, dir);
    CHECK(r.status == 2);
    CHECK(r.err.find("--schemes") != std::string::npos);
    no_files();
  }
  SECTION("missing --out") {
    const auto r = run_lgi("stress --quick", dir);
    CHECK(r.status == 2);
    CHECK(r.err.find("--out") != std::string::npos);
    no_files();
  }
  SECTION("non-positive --budget") {
    const auto r = run_lgi("stress --quick --budget 0 --out " + out, dir);
    CHECK(r.status == 2);
    CHECK(r.err.find("--budget") != std::string::npos);
    no_files();
  }
  SECTION("--schemes restricts, and an existing file is kept unless --force") {
    const auto r = run_lgi("stress --quick --schemes rkmk4,exact --out " + out, dir);
    INFO("stderr: " << r.err);
    REQUIRE(r.status == 0);
    const Table t = read_results(out);
    REQUIRE(t.size() > 0);
    for (const auto& s : t.scheme) CHECK((s == "rkmk4" || s == "exact"));
    // exact refuses every scene with a torque, with the registry's reason.
    for (std::size_t i = 0; i < t.size(); ++i)
      if (t.scheme[i] == "exact" && (t.case_id[i] == "stiffness" || t.case_id[i] == "theta-pi")) {
        CHECK(t.outcome[i] == "refused");
        CHECK(t.reason[i].find("free body") != std::string::npos);
        CHECK(t.pass[i] == 1.0);
      }
    const auto size = fs::file_size(out);
    const auto again = run_lgi("stress --quick --schemes rkmk4 --out " + out, dir);
    CHECK(again.status == 2);
    CHECK(again.err.find("exists") != std::string::npos);
    CHECK(fs::file_size(out) == size);
    const auto forced = run_lgi("stress --quick --schemes rkmk4 --force --quiet --out " + out, dir);
    CHECK(forced.status == 0);
    CHECK(forced.out.empty());
    CHECK(read_results(out).size() < t.size());
  }
}

}  // namespace test_stress

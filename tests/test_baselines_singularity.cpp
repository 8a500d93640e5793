// The Boost.Odeint baselines (integrators/baselines/) in use: the
// Euler-angle singularity detected and reported (never a silent wrong
// answer), the quaternion's norm drift in the trajectory file, the work
// counters in /diagnostics, the rotation vector's chart switch, and
// `lgi singularity` end to end.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

// First: it includes odeint with a GCC false positive silenced (see there).
#include "support/reference_solution.hpp"

#include "experiments/io/scene_reader.hpp"
#include "integrators/baselines/baselines.hpp"
#include "integrators/baselines/euler_zxz.hpp"
#include "integrators/baselines/matrix.hpp"
#include "integrators/baselines/quaternion.hpp"
#include "integrators/baselines/rotation_vector.hpp"
#include "integrators/registry/registry.hpp"
#include "support/baseline_runs.hpp"
#include "support/h5_read.hpp"
#include "support/run_command.hpp"

namespace test_baselines_singularity {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using integrators::RunConfig;
using integrators::RunStats;
using lie::Mat3;
namespace bl = integrators::baselines;
namespace fs = std::filesystem;

using namespace lgi::testing;

TEST_CASE("the Euler-angle singularity is detected and reported, never a silent wrong answer",
          "[baselines][singularity]") {
  SECTION("every euler-zxz stepper on heavy_top_trindade_singular stops at the first pass near theta = pi") {
    const system::Scene sc = scene("heavy_top_trindade_singular");
    const system::AnyModel model = system::make_model(sc);
    for (bl::Stepper s : bl::all_steppers) {
      system::State x = sc.initial;
      const RunStats st = run(bl::Coordinates::euler_zxz, s, model, x, sc.t_end.value(), s == bl::Stepper::rk4 ? 1e-3 : 1e-8);
      INFO(bl::stepper_name(s) << ": " << st.status);
      CHECK_FALSE(st.ok);
      CHECK(st.status.find("Euler-angle singularity") != std::string::npos);
      CHECK(st.status.find("theta = ") != std::string::npos);
      CHECK(st.status.find("t = ") != std::string::npos);
      CHECK(st.t_final < 0.05);  // θ0 = 3.14, θ̇0 = 0.5: the first pass is at t ≈ 3 ms
      CHECK(x.R.allFinite());
    }
  }
  SECTION("a start on the singular set fails at once") {
    const system::Scene sc = scene("free_body_hlw");  // identity attitude: θ = 0
    const system::AnyModel model = system::make_model(sc);
    system::State x = sc.initial;
    const RunStats st = run(bl::Coordinates::euler_zxz, bl::Stepper::dopri5, model, x, 1.0, 1e-8);
    CHECK_FALSE(st.ok);
    CHECK(st.status.find("Euler-angle singularity") != std::string::npos);
    CHECK(st.steps == 0);
  }
  SECTION("on heavy_top_trindade_4 every euler-zxz run is either right or stops naming the singularity") {
    // The slow top falls through θ ≈ π at |sinθ| ≈ 6e-4, where ψ̇ reaches ~1e4 rad/s.
    const system::Scene sc = scene("heavy_top_trindade_4");
    const system::AnyModel model = system::make_model(sc);
    const double T = 4.0;
    const system::State ref = rkmk4_at(model, sc.initial, T, 1e-4);
    int ok_runs = 0;
    for (bl::Stepper s : bl::all_steppers) {
      for (double p : s == bl::Stepper::rk4 ? std::vector<double>{1e-2, 1e-3, 1e-4} : std::vector<double>{1e-6, 1e-9}) {
        system::State x = sc.initial;
        const RunStats st = run(bl::Coordinates::euler_zxz, s, model, x, T, p);
        INFO(bl::stepper_name(s) << " at " << p << ": " << st.status);
        if (st.ok) {
          if (s != bl::Stepper::rk4 && s != bl::Stepper::bs) ++ok_runs;
          const double tolerance = s == bl::Stepper::rk4 ? 1e-2 : 1e3 * p;
          CHECK(attitude_error(x.R, ref.R) <= tolerance);
        } else {
          CHECK(st.status.find("Euler-angle singularity") != std::string::npos);
        }
      }
    }
    // dopri5, rkf78 and rosenbrock4 resolve the pass at both tolerances (bs at
    // 1e-6 steps across θ = π and is stopped; rk4 at these steps is stopped).
    CHECK(ok_runs == 6);
  }
  SECTION("lgi simulate exits 1, keeps the .partial file and names the singularity") {
    const std::string dir = testing::scratch_dir("baselines_singular");
    const std::string out = dir + "/e.h5";
    const auto r = testing::run_lgi("simulate --scene " + scenes +
                                    "/heavy_top_trindade_singular.toml --scheme euler-zxz/dopri5 --tol 1e-8 --out " +
                                    out);
    INFO(r.err);
    CHECK(r.status == 1);
    CHECK(testing::line_count(r.err) == 1);
    CHECK(r.err.find("Euler-angle singularity") != std::string::npos);
    CHECK_FALSE(fs::exists(out));
    REQUIRE(fs::exists(out + ".partial"));
    CHECK(testing::read_string_attribute(out + ".partial", "/diagnostics", "status").find("Euler-angle singularity") !=
          std::string::npos);
    const auto angles = testing::read_dataset(out + ".partial", "/particles/body/euler_zxz/value");
    REQUIRE(angles.shape.size() == 3);
    CHECK(angles.shape[0] >= 1);
  }
}

TEST_CASE("quat shows its norm drift in /observables/orthogonality_error; quat-normalized does not",
          "[baselines][drift]") {
  const std::string dir = testing::scratch_dir("baselines_drift");
  const std::string top = scenes + "/heavy_top_trindade_1.toml";
  auto last_and_max = [&](const std::string& scheme, const std::string& file) {
    const auto r = testing::run_lgi("simulate --scene " + top + " --scheme " + scheme +
                                    " --dt 5e-3 --t-end 10 --save-every 100 --quiet --out " + file);
    INFO(r.err);
    REQUIRE(r.status == 0);
    const auto e = testing::read_dataset(file, "/observables/orthogonality_error/value");
    double mx = 0.0;
    for (double v : e.data) mx = std::max(mx, v);
    return std::pair{e.data.back(), mx};
  };
  const auto [quat_last, quat_max] = last_and_max("quat/rk4", dir + "/q.h5");
  const auto [norm_last, norm_max] = last_and_max("quat-normalized/rk4", dir + "/qn.h5");
  const auto [matrix_last, matrix_max] = last_and_max("matrix/rk4", dir + "/m.h5");
  INFO("quat " << quat_last << ", quat-normalized max " << norm_max << ", matrix " << matrix_last);
  CHECK(quat_last > 1e-6);     // the drift, far above round-off
  CHECK(norm_max < 1e-13);     // projected every step
  CHECK(matrix_last > 1e-6);   // R in R^9 drifts too
  (void)quat_max;
  (void)norm_last;
  (void)matrix_max;

  SECTION("the observer's R for quat is q v q*, so |R^T R - I| = sqrt(3) ||q|^4 - 1| whatever the attitude") {
    struct Check final : integrators::Observer {
      double worst_isotropy = 0.0, last_error = 0.0;
      void observe(std::int64_t, double, const system::State& s) override {
        const Mat3 G = s.R.transpose() * s.R;
        const double c = G.trace() / 3.0;  // |q|^4
        worst_isotropy = std::max(worst_isotropy, (G - c * Mat3::Identity()).norm());
        last_error = std::abs(lie::orthogonality_error(s.R) - std::sqrt(3.0) * std::abs(c - 1.0));
      }
    } check;
    const system::Scene sc = scene("heavy_top_trindade_1");
    const system::AnyModel model = system::make_model(sc);
    system::State x = sc.initial;
    RunConfig cfg;
    cfg.t_end = 10.0;
    cfg.dt = 5e-3;
    cfg.save_every = 100;
    REQUIRE(bl::run_baseline(bl::Coordinates::quat, bl::Stepper::rk4, model, x, cfg, check).ok);
    CHECK(check.worst_isotropy < 1e-12);
    CHECK(check.last_error < 1e-12);
  }
}

TEST_CASE("steps, rejected steps and right-hand-side evaluations reach /diagnostics for every baseline",
          "[baselines][counts]") {
  const std::string dir = testing::scratch_dir("baselines_counts");
  const std::string top = scenes + "/heavy_top_trindade_1.toml";
  for (bl::Coordinates c : bl::all_coordinates)
    for (bl::Stepper s : bl::all_steppers) {
      const std::string name = bl::baseline_name(c, s);
      std::string file = name;
      for (char& ch : file)
        if (ch == '/') ch = '_';
      file = dir + "/" + file + ".h5";
      const std::string step = s == bl::Stepper::rk4 ? " --dt 1e-3" : " --tol 1e-6";
      const auto r = testing::run_lgi("simulate --scene " + top + " --scheme " + name + step +
                                      " --t-end 0.5 --save-every 1000 --out " + file);
      INFO(name << ": " << r.err << r.out);
      REQUIRE(r.status == 0);
      auto attr = [&](const char* a) { return testing::read_integer_attribute(file, "/diagnostics", a); };
      const std::int64_t steps = attr("steps"), rejected = attr("rejected_steps"), rhs = attr("rhs_evaluations");
      INFO("steps " << steps << " rejected " << rejected << " rhs " << rhs);
      CHECK(steps > 0);
      CHECK(rejected >= 0);
      const std::int64_t attempts = steps + rejected;
      const bool projects = c == bl::Coordinates::quat_normalized || c == bl::Coordinates::rotvec;
      switch (s) {
        case bl::Stepper::rk4: CHECK(rhs == 4 * steps); break;
        // 2 for the starting step, 1 for ẋ(t0), 6 per attempt (FSAL); a rotvec
        // chart switch costs one more (quat-normalized rescales ẋ exactly).
        case bl::Stepper::dopri5:
          if (c == bl::Coordinates::rotvec) CHECK(rhs >= 3 + 6 * attempts);
          else CHECK(rhs == 3 + 6 * attempts);
          break;
        // 2 + ẋ at every accepted state but the last + 12 per attempt.
        case bl::Stepper::rkf78: CHECK(rhs == 2 + steps + 12 * attempts); break;
        case bl::Stepper::rosenbrock4: CHECK(rhs == 2 + 6 * attempts); break;
        case bl::Stepper::bs: CHECK(rhs > 2 * attempts); break;
      }
      (void)projects;
      CHECK(testing::read_string_attribute(file, "/diagnostics", "status") == "ok");
    }
}

TEST_CASE("the rotation vector switches chart at |Psi| > pi and stays accurate", "[baselines][rotvec]") {
  // A 50 rad/s spin takes |Psi| past pi every 0.06 s; without the switch the
  // kinematics would reach its singularity at |Psi| = 2 pi within 0.13 s.
  const system::Scene sc = scene("heavy_top_trindade_1");
  const system::AnyModel model = system::make_model(sc);
  struct Max final : integrators::Observer {
    double max_angle = 0.0;
    void observe(std::int64_t, double, const system::State& s) override {
      max_angle = std::max(max_angle, lie::log_so3(s.R).norm());
    }
  } obs;
  system::State x = sc.initial;
  RunConfig cfg;
  cfg.t_end = 1.0;
  cfg.tol = 1e-10;
  REQUIRE(bl::run_baseline(bl::Coordinates::rotvec, bl::Stepper::dopri5, model, x, cfg, obs).ok);
  const system::State ref = testing::reference_solution(std::get<system::SceneModel>(model), sc.initial, 0.0, 1.0, 1e-14);
  CHECK(attitude_error(x.R, ref.R) < 1e-8);
  CHECK(obs.max_angle > 3.0);
}

TEST_CASE("lgi singularity --quick runs end to end", "[baselines][study]") {
  const std::string dir = testing::scratch_dir("baselines_study");
  const std::string out = dir + "/s.h5";
  const auto r = testing::run_lgi("singularity --quick --out " + out);
  INFO(r.err << r.out);
  REQUIRE(r.status == 0);
  REQUIRE(fs::exists(out));
  REQUIRE(fs::exists(dir + "/s.csv"));
  CHECK_FALSE(fs::exists(out + ".partial"));
  CHECK(testing::read_string_attribute(out, "/h5md/creator", "name") == "lgi");
  CHECK_FALSE(testing::read_string_attribute(out, "/parameters", "compiler").empty());
  const std::string guarded = "/scenes/trindade_singular/runs/euler-zxz_dopri5";
  CHECK(testing::read_string_attribute(out, guarded, "outcome") == "failed");
  CHECK(testing::read_string_attribute(out, guarded, "status").find("Euler-angle singularity") != std::string::npos);
  // The unguarded run goes through the passes; its raw angles and θ̇ are recorded.
  const std::string unguarded = "/scenes/trindade_singular/runs/euler-zxz_dopri5_unguarded";
  const auto theta = testing::read_dataset(out, unguarded + "/euler_zxz/theta");
  const auto psi = testing::read_dataset(out, unguarded + "/euler_zxz/psi");
  const auto thetadot = testing::read_dataset(out, unguarded + "/euler_zxz/theta_dot");
  CHECK(theta.data.size() > 10);
  CHECK(psi.data.size() == theta.data.size());
  CHECK(thetadot.data.size() == theta.data.size());
  const auto h = testing::read_dataset(out, unguarded + "/step_history/step_size");
  CHECK(h.data.size() > 10);
  // Where the Lie-group schemes and the quaternion baseline succeed, the centres of mass agree.
  for (const char* run : {"rkmk-dp54", "quat_dopri5", "rkmk4"}) {
    const auto d = testing::read_dataset(out, std::string("/scenes/trindade_singular/runs/") + run + "/com_deviation");
    double mx = 0.0;
    for (double v : d.data)
      if (std::isfinite(v)) mx = std::max(mx, v);
    INFO(run << ": max c.o.m. deviation " << mx);
    CHECK(mx < 1e-5);
  }
  std::ifstream csv(dir + "/s.csv");
  std::string header;
  std::getline(csv, header);
  CHECK(header.rfind("scene,method,", 0) == 0);
  int rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  CHECK(rows >= 10);
}

TEST_CASE("the full singularity study: guarded Euler angles stop, everything that succeeds agrees", "[baselines][study][slow]") {
  const std::string dir = testing::scratch_dir("baselines_study_full");
  const std::string out = dir + "/full.h5";
  const auto r = testing::run_lgi("singularity --quiet --out " + out);
  INFO(r.err);
  REQUIRE(r.status == 0);
  auto strings = [&](const char* name) { return testing::read_string_dataset(out, name); };
  const auto scene_col = strings("/results/scene"), method = strings("/results/method"),
             outcome = strings("/results/outcome"), status = strings("/results/status"),
             coordinates = strings("/results/coordinates"), guard = strings("/results/guard");
  const auto dev = testing::read_dataset(out, "/results/com_max_deviation");
  REQUIRE(method.size() == dev.data.size());
  int guarded_failures = 0;
  for (std::size_t i = 0; i < method.size(); ++i) {
    INFO(scene_col[i] << " " << method[i] << ": " << outcome[i] << ", " << status[i] << ", deviation " << dev.data[i]);
    // The study's columns, not the method's name (experiments/SINGULARITY.md).
    const bool euler = coordinates[i] == "euler-zxz";
    const bool unguarded = guard[i] == "off";
    if (euler && !unguarded && scene_col[i] == "trindade_singular") {
      CHECK(outcome[i] == "failed");
      CHECK(status[i].find("Euler-angle singularity") != std::string::npos);
      ++guarded_failures;
      continue;
    }
    if (!euler) CHECK(outcome[i] == "ok");
    if (outcome[i] != "ok") {
      CHECK(status[i].find("Euler-angle singularity") != std::string::npos);
      continue;
    }
    if (method[i] == "euler-zxz/rk4 (unguarded)") {
      CHECK(dev.data[i] > 1e-3);  // the silent wrong answer the guard prevents
      continue;
    }
    const bool second_order = method[i] == "lgvi" || method[i] == "split-exact" || method[i] == "simo-wong";
    CHECK(dev.data[i] < (second_order ? 1e-4 : 1e-5));
  }
  CHECK(guarded_failures == 5);
}

}  // namespace test_baselines_singularity

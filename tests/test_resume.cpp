// Resuming a run from a checkpoint (integrators/core/run_config.hpp, Checkpoints;
// scheme_interface.hpp, "Resume"), for every registered scheme: one that the
// registry calls resumable, resumed at a checkpoint taken by the loop, goes on
// bit for bit as the run that never stopped (every sample after the
// checkpoint, the final state, the step count and every work counter); one
// that is not refuses a resume (the run fails with "cannot resume"). Also the
// checkpoint slots of lgi long-time (experiments/io/run_checkpoint.hpp):
// round trip, and torn or damaged slots read as empty.
#include <catch2/catch.hpp>
#include <cstring>
#include <map>
#include <optional>
#include <vector>

#include "experiments/io/run_checkpoint.hpp"
#include "experiments/io/scene_reader.hpp"
#include "integrators/registry/registry.hpp"
#include "support/recorder.hpp"

namespace test_resume {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using testing::Recorder;
using testing::Sample;

namespace {

const std::string scenes = LGI_SCENES_DIR;

/// Keeps the checkpoint offered at step `at`.
class KeepOne final : public integrators::Checkpoints {
 public:
  explicit KeepOne(std::int64_t at) : at_(at) { every = 1; }
  bool due(std::int64_t step) override { return step == at_; }
  void save(const integrators::LoopCheckpoint& c) override { kept = c; }
  std::optional<integrators::LoopCheckpoint> kept;

 private:
  std::int64_t at_;
};

bool same(const system::State& a, const system::State& b) {
  return std::memcmp(a.R.data(), b.R.data(), sizeof(double) * 9) == 0 &&
         std::memcmp(a.Pi.data(), b.Pi.data(), sizeof(double) * 3) == 0;
}

bool same(const integrators::WorkCounters& a, const integrators::WorkCounters& b) {
  return a.rhs_evaluations == b.rhs_evaluations && a.rejected_steps == b.rejected_steps &&
         a.newton_iterations_max == b.newton_iterations_max && a.newton_failures == b.newton_failures;
}

}  // namespace

TEST_CASE("a resumed run goes on bit for bit; a scheme that cannot be resumed refuses", "[resume]") {
  const system::Scene free = experiments::read_scene(scenes + "/free_body_hlw.toml");
  const system::Scene top = experiments::read_scene(scenes + "/heavy_top_trindade_1.toml");
  const system::AnyModel free_model = system::make_model(free), top_model = system::make_model(top);
  std::map<bool, int> count;
  for (const auto& scheme : integrators::scheme_registry()) {
    const bool on_top = integrators::unsupported_reason(scheme, top_model).empty();
    const system::Scene& scene = on_top ? top : free;
    const system::AnyModel& model = on_top ? top_model : free_model;
    integrators::RunConfig cfg;
    cfg.t_end = on_top ? 0.2 : 2.0;
    cfg.dt = cfg.t_end / 200;
    if (scheme.properties.adaptive) cfg.tol = 1e-10, cfg.dt = 0.0;
    INFO(scheme.name << " on " << scene.file);

    // A plain run, then one offered checkpoints (the same steps: offering one changes nothing).
    Recorder plain, whole;
    system::State x0 = scene.initial, x = scene.initial;
    const integrators::RunStats first = scheme.run(model, x0, cfg, plain);
    REQUIRE(first.ok);
    REQUIRE(first.steps >= 4);
    KeepOne keep(first.steps / 2);
    integrators::RunConfig c = cfg;
    c.checkpoints = &keep;
    const integrators::RunStats straight = scheme.run(model, x, c, whole);
    REQUIRE(straight.ok);
    CHECK(straight.steps == first.steps);
    CHECK(same(x, x0));
    CHECK(keep.kept.has_value() == scheme.resumable);
    ++count[scheme.resumable];

    integrators::LoopCheckpoint from;
    if (keep.kept) from = *keep.kept;
    else from.step = first.steps / 2, from.t = cfg.t_end / 2, from.state = scene.initial;  // to one that cannot resume
    KeepOne resume_only(-1);
    resume_only.resume_from = &from;
    Recorder rest;
    system::State y = scene.initial;
    c.checkpoints = &resume_only;
    const integrators::RunStats resumed = scheme.run(model, y, c, rest);
    if (!scheme.resumable) {
      CHECK_FALSE(resumed.ok);
      CHECK(resumed.status.find("cannot resume") != std::string::npos);
      continue;
    }
    REQUIRE(resumed.ok);
    CHECK(resumed.steps == straight.steps);
    CHECK(same(resumed.work, straight.work));
    CHECK(same(y, x));
    // The samples after the checkpoint: the same steps, times and states, bit for bit.
    std::vector<Sample> after;
    for (const Sample& s : whole.samples)
      if (s.step > from.step) after.push_back(s);
    REQUIRE(rest.samples.size() == after.size());
    for (std::size_t i = 0; i < after.size(); ++i) {
      CHECK(rest.samples[i].step == after[i].step);
      CHECK(std::memcmp(&rest.samples[i].t, &after[i].t, sizeof(double)) == 0);
      CHECK(same(rest.samples[i].s, after[i].s));
    }
  }
  CHECK(count[true] > 0);  // the explicit RKMK schemes, at least
}

TEST_CASE("checkpoint slots: round trip, and a torn or damaged slot reads as empty", "[resume]") {
  experiments::RunCheckpoint c;
  c.rows = 17;
  c.loop.step = 4096;
  c.loop.t = 4.096;
  c.loop.h = 1e-3;
  c.loop.state.R = lie::Mat3::Identity();
  c.loop.state.Pi = lie::Vec3(0.1, -0.2, 0.3);
  c.loop.work = {12, 3, 4, 5};
  c.loop.memory = {1.0, 0.0, 2.5};
  c.cpu_seconds = 1.5;
  c.output_seconds = 0.25;
  c.window_max = {1e-16, 2e-16};
  c.run_max = {3e-16, 4e-16};
  const std::vector<unsigned char> slot = experiments::encode_checkpoint(c, 7);
  REQUIRE(slot.size() == experiments::checkpoint_slot_bytes);
  const auto back = experiments::decode_checkpoint(slot, 2);
  REQUIRE(back);
  CHECK(back->second == 7);
  CHECK(back->first.rows == 17);
  CHECK(back->first.loop.step == 4096);
  CHECK(same(back->first.loop.state, c.loop.state));
  CHECK(same(back->first.loop.work, c.loop.work));
  CHECK(back->first.loop.memory == c.loop.memory);
  CHECK(back->first.window_max == c.window_max);
  CHECK(back->first.run_max == c.run_max);
  CHECK_FALSE(experiments::decode_checkpoint(slot, 3));  // another number of error columns
  for (std::size_t at : {0u, 9u, 20u, 40u, 100u}) {  // any changed byte: magic, header, payload
    std::vector<unsigned char> damaged = slot;
    damaged[at] ^= 0x40;
    CHECK_FALSE(experiments::decode_checkpoint(damaged, 2));
  }
  CHECK_FALSE(experiments::decode_checkpoint(std::vector<unsigned char>(slot.begin(), slot.begin() + 100), 2));
  // Two slots: the newest intact one with no more rows than the table has.
  std::vector<unsigned char> record = experiments::encode_checkpoint(c, 8);
  c.rows = 10;
  const std::vector<unsigned char> older = experiments::encode_checkpoint(c, 3);
  record.insert(record.end(), older.begin(), older.end());
  std::uint64_t next = 0;
  CHECK(experiments::newest_checkpoint(record, 2, 100, next)->rows == 17);
  CHECK(next == 9);
  CHECK(experiments::newest_checkpoint(record, 2, 12, next)->rows == 10);
  CHECK_FALSE(experiments::newest_checkpoint(record, 2, 5, next));
  record[40] ^= 1;  // the newer slot torn
  CHECK(experiments::newest_checkpoint(record, 2, 100, next)->rows == 10);
  CHECK(next == 4);
}

}  // namespace test_resume

#pragma once
// An observer that keeps every sample it is shown (step, time, state) and
// counts the on_stop() calls, for the time-loop and resume tests.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "integrators/registry/registry.hpp"

namespace lgi::testing {

struct Sample {
  std::int64_t step;
  double t;
  system::State s;
};

class Recorder final : public integrators::Observer {
 public:
  void observe(std::int64_t step, double t, const system::State& s) override { samples.push_back({step, t, s}); }
  void on_stop() override {
    ++stops;
    samples_at_stop = samples.size();
  }
  std::vector<Sample> samples;
  int stops = 0;
  std::size_t samples_at_stop = 0;
};

}  // namespace lgi::testing

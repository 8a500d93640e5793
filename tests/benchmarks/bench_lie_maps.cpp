// Nanoseconds per call of the SO(3) maps every scheme leans on.
#include <benchmark/benchmark.h>

#include "lie/so3.hpp"

using namespace lgi::lie;

namespace {

// A spread of arguments so no branch is predicted for free.
const Vec3 arguments[4] = {Vec3(0.3, -0.2, 0.1), Vec3(1.0, 0.5, -0.7), Vec3(2e-3, 1e-3, -1e-3), Vec3(-2.0, 1.0, 1.5)};

void exp_so3_bench(benchmark::State& state) {
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(exp_so3(arguments[i++ & 3]));
}
void log_so3_bench(benchmark::State& state) {
  Mat3 R[4];
  for (int k = 0; k < 4; ++k) R[k] = exp_so3(arguments[k]);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(log_so3(R[i++ & 3]));
}
void cay_bench(benchmark::State& state) {
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(cay(arguments[i++ & 3]));
}
void dexpinv_body_bench(benchmark::State& state) {
  const Vec3 w(0.4, -1.0, 2.0);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(dexpinv_body(arguments[i++ & 3], w));
}

}  // namespace

BENCHMARK(exp_so3_bench)->Name("exp_so3");
BENCHMARK(log_so3_bench)->Name("log_so3");
BENCHMARK(cay_bench)->Name("cay");
BENCHMARK(dexpinv_body_bench)->Name("dexpinv_body");

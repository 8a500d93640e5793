// What bounds a dmv-pre10 step (README, Performance, "The arithmetic limit"):
//  - limits/scalar_peak: the core's rate of scalar double additions and
//    multiplications, 7 independent chains of each (enough to cover their
//    latencies), as scalar_flops_per_ns. A step's operation count over this
//    rate is its issue limit.
//  - limits/dmv-pre10/one and limits/dmv-pre10/two_interleaved (Hairer &
//    Vilmart's body, tests/benchmarks/scenes/, at h = 0.01): one
//    trajectory stepped alone, and two stepped in alternation (ns per step of
//    one trajectory). A step bound by its chain of dependent operations
//    (Π → f → Π) would overlap with the other trajectory's and cost less per
//    step in alternation; a step bound by throughput costs the same.
//  - limits/dmv-update/matrix and limits/dmv-update/quaternion: the state
//    update of a free-body DMV step alone, Π ← cay(2f)ᵀ Π with R ← R cay(2f)
//    (moser_veselov::apply_cayley_step), and with the attitude as a unit
//    quaternion q ← q (1, f)/√(1 + |f|²) instead (written here only to be
//    timed), both as compensated sums, over a sequence of slightly varying f;
//    and .../quaternion_and_matrix, with R formed from q after every update,
//    as a step would for the loop that reads R (README, "The arithmetic limit":
//    the quaternion was not built).
// scripts/benchmark_ratios.py prints the three on one line, outside the per-scheme table.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstddef>
#include <string>
#include <variant>

#include "experiments/io/scene_reader.hpp"
#include "integrators/moser_veselov.hpp"
#include "integrators/system/model.hpp"
#include "lie/quaternion.hpp"

using namespace lgi;

namespace {

void scalar_peak(benchmark::State& state) {
#if defined(__x86_64__)
  constexpr std::int64_t rounds = 1 << 16;
  static const double one = 1.0;
  for (auto _ : state) {
    // 7 addsd and 7 mulsd chains on xmm0–xmm13, all set to 1 first (a denormal or NaN left in a
    // register by earlier code could take a slow path); xmm14 = 0 and xmm15 = 1 keep them at 1.
    asm volatile(
        "pxor %%xmm14, %%xmm14\n\t"
        "movsd %1, %%xmm15\n\t"
        "movapd %%xmm15, %%xmm0\n\t movapd %%xmm15, %%xmm1\n\t movapd %%xmm15, %%xmm2\n\t"
        "movapd %%xmm15, %%xmm3\n\t movapd %%xmm15, %%xmm4\n\t movapd %%xmm15, %%xmm5\n\t"
        "movapd %%xmm15, %%xmm6\n\t movapd %%xmm15, %%xmm7\n\t movapd %%xmm15, %%xmm8\n\t"
        "movapd %%xmm15, %%xmm9\n\t movapd %%xmm15, %%xmm10\n\t movapd %%xmm15, %%xmm11\n\t"
        "movapd %%xmm15, %%xmm12\n\t movapd %%xmm15, %%xmm13\n\t"
        "mov %0, %%rcx\n\t"
        "1:\n\t"
        "addsd %%xmm14, %%xmm0\n\t mulsd %%xmm15, %%xmm7\n\t addsd %%xmm14, %%xmm1\n\t mulsd %%xmm15, %%xmm8\n\t"
        "addsd %%xmm14, %%xmm2\n\t mulsd %%xmm15, %%xmm9\n\t addsd %%xmm14, %%xmm3\n\t mulsd %%xmm15, %%xmm10\n\t"
        "addsd %%xmm14, %%xmm4\n\t mulsd %%xmm15, %%xmm11\n\t addsd %%xmm14, %%xmm5\n\t mulsd %%xmm15, %%xmm12\n\t"
        "addsd %%xmm14, %%xmm6\n\t mulsd %%xmm15, %%xmm13\n\t"
        "dec %%rcx\n\t"
        "jnz 1b\n\t"
        :
        : "r"(rounds), "m"(one)
        : "rcx", "xmm0", "xmm1", "xmm2", "xmm3", "xmm4", "xmm5", "xmm6", "xmm7", "xmm8", "xmm9", "xmm10", "xmm11",
          "xmm12", "xmm13", "xmm14", "xmm15", "cc");
  }
  state.counters["scalar_flops_per_ns"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * static_cast<double>(rounds) * 14.0 * 1e-9, benchmark::Counter::kIsRate);
#else
  state.SkipWithError("x86-64 only");
#endif
}

const system::Scene& hairer_vilmart() {
  static const system::Scene scene =
      experiments::read_scene(std::string(LGI_BENCH_SCENES_DIR) + "/free_body_hairer_vilmart.toml");
  return scene;
}

// Trajectories of 2048 steps of h = 0.01 from Π0 (and from 1.01 Π0 for the second).
template <std::size_t Trajectories>
void dmv_pre10_steps(benchmark::State& state) {
  constexpr int steps = 2048;
  constexpr double h = 0.01;
  const system::Scene& scene = hairer_vilmart();
  const system::AnyModel model = system::make_model(scene);
  const auto& body = std::get<system::FreeBody>(model);
  for (auto _ : state) {
    system::State x[Trajectories];
    integrators::DmvPreprocessed<10> scheme[Trajectories];
    integrators::WorkCounters work;
    bool failed = false;
    for (std::size_t j = 0; j < Trajectories; ++j) {
      x[j] = scene.initial;
      x[j].Pi *= 1.0 + 0.01 * static_cast<double>(j);
      scheme[j].start(body, x[j], 0.0);
    }
    for (int k = 0; k < steps; ++k)
      for (std::size_t j = 0; j < Trajectories; ++j)
        if (!scheme[j].step(body, x[j], k * h, h, work).converged) failed = true;
    if (failed) {
      state.SkipWithError("a step did not converge");
      break;
    }
    benchmark::DoNotOptimize(x);
  }
  state.counters["ns_per_step"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * steps * static_cast<double>(Trajectories) * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// The quaternion of cay(2f) is (1, f)/r with r = √(1 + |f|²); with d = 1/(r (1 + r)),
// 1/r = (1 + r) d and 1/r − 1 = −|f|² d, so q's increment q ⊗ ((1, f)/r − 1) is
// (1/r − 1) q + (1/r) q ⊗ (0, f), without cancellation. Π as in apply_cayley_step.
struct QuaternionState {
  double q[4] = {1.0, 0.0, 0.0, 0.0}, q_carry[4] = {};
  double P[3] = {}, P_carry[3] = {};
};
[[gnu::always_inline]] inline void apply_cayley_step_quaternion(const lie::Vec3& f, QuaternionState& s) {
  const double x = f.x(), y = f.y(), z = f.z();
  const double xx = x * x, yy = y * y, zz = z * z, ff = (xx + yy) + zz;
  const double c = 2.0 / (1.0 + ff);
  const double xy = x * y, xz = x * z, yz = y * z;
  const double N[9] = {-(yy + zz), xy - z, xz + y, xy + z, -(xx + zz), yz - x, xz - y, yz + x, -(xx + yy)};
  double dP[3];
  for (int j = 0; j < 3; ++j) dP[j] = c * ((N[j] * s.P[0] + N[3 + j] * s.P[1]) + N[6 + j] * s.P[2]);
  for (int j = 0; j < 3; ++j) integrators::add_compensated(s.P[j], dP[j], s.P_carry[j]);
  const double r = std::sqrt(1.0 + ff), d = 1.0 / (r * (1.0 + r));
  const double inv_r = (1.0 + r) * d, inv_r_minus_1 = -ff * d;
  const double w = s.q[0], a = s.q[1], b = s.q[2], e = s.q[3];
  const double p[4] = {-((a * x + b * y) + e * z), w * x + (b * z - e * y), w * y + (e * x - a * z),
                       w * z + (a * y - b * x)};  // q ⊗ (0, f)
  for (int k = 0; k < 4; ++k) integrators::add_compensated(s.q[k], inv_r_minus_1 * s.q[k] + inv_r * p[k], s.q_carry[k]);
}

enum class Attitude { matrix, quaternion, quaternion_and_matrix };

// 2048 updates with f near Hairer & Vilmart's body's at h = 0.01 (|f| ≈ 0.01).
template <Attitude A>
void dmv_update(benchmark::State& state) {
  constexpr int steps = 2048;
  for (auto _ : state) {
    system::State x{lie::Mat3::Identity(), lie::Vec3(1.8, 0.4, -0.9)};
    integrators::moser_veselov::Carry carry;
    QuaternionState qs;
    qs.P[0] = 1.8, qs.P[1] = 0.4, qs.P[2] = -0.9;
    for (int k = 0; k < steps; ++k) {
      const lie::Vec3 f(0.009, 0.0025 + 1e-12 * (k & 7), -0.0045);
      if constexpr (A == Attitude::matrix) {
        integrators::moser_veselov::apply_cayley_step(f, x, carry);
      } else {
        apply_cayley_step_quaternion(f, qs);
        if constexpr (A == Attitude::quaternion_and_matrix)
          x.R = lie::matrix_from_quat(Eigen::Quaterniond(qs.q[0], qs.q[1], qs.q[2], qs.q[3]));
      }
      // The state is in memory after every step, as the time loop's is.
      benchmark::DoNotOptimize(x);
      benchmark::DoNotOptimize(qs);
    }
  }
  state.counters["ns_per_step"] = benchmark::Counter(static_cast<double>(state.iterations()) * steps * 1e-9,
                                                     benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK(scalar_peak)->Name("limits/scalar_peak");
BENCHMARK(dmv_pre10_steps<1>)->Name("limits/dmv-pre10/one");
BENCHMARK(dmv_pre10_steps<2>)->Name("limits/dmv-pre10/two_interleaved");
BENCHMARK(dmv_update<Attitude::matrix>)->Name("limits/dmv-update/matrix");
BENCHMARK(dmv_update<Attitude::quaternion>)->Name("limits/dmv-update/quaternion");
BENCHMARK(dmv_update<Attitude::quaternion_and_matrix>)->Name("limits/dmv-update/quaternion_and_matrix");

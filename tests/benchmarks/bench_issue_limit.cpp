// What bounds a dmv-pre10 step (docs/performance.md §3, "The arithmetic limit"):
//  - limits/scalar_peak: the core's rate of scalar double additions and
//    multiplications, 7 independent chains of each (enough to cover their
//    latencies), as scalar_flops_per_ns. A step's operation count over this
//    rate is its issue limit.
//  - limits/vector_peak/<isa> (sse2, avx2, avx512, where this CPU has them):
//    the same 7 + 7 chains on packed doubles (xmm, ymm, zmm), as
//    lane_flops_per_ns, operations times lanes. Over the scalar peak it is the
//    most an ensemble kernel (docs/ensemble.md) can gain over the scalar loop
//    when the scalar step is bound by throughput: a core whose vector units
//    are narrower than the vector (AMD Zen 1 executes a 256-bit operation as
//    two 128-bit halves) gains less than the lanes.
//  - limits/dmv-pre10/one and limits/dmv-pre10/two_interleaved (Hairer &
//    Vilmart's body, tests/benchmarks/scenes/, at h = 0.01): one
//    trajectory stepped alone, and two stepped in alternation (ns per step of
//    one trajectory). A step bound by its chain of dependent operations
//    (Π → f → Π) would overlap with the other trajectory's and cost less per
//    step in alternation; a step bound by throughput costs the same.
//    The steps are the time loop's (step_keeping_attitude: the attitude kept
//    as a quaternion, R not formed; stepper_loop.hpp, "Kept attitude").
//  - limits/dmv-update/matrix and limits/dmv-update/quaternion: the state
//    update of a free-body DMV step alone, Π ← cay(2f)ᵀ Π with R ← R cay(2f)
//    (moser_veselov::apply_cayley_step, as dmv and lgvi take it), and with the
//    attitude as a unit quaternion q ← q ⊗ (1, f)/√(1 + |f|²) instead (the
//    preprocessed schemes' on a free body, cayley_quaternion.hpp), both as
//    compensated sums, over a sequence of slightly varying f; and
//    .../quaternion_and_matrix, with R formed from q after every update, as a
//    step for a caller that reads R after every step (step()).
// scripts/benchmark_ratios.py prints the scalar peak and the two dmv-pre10 figures on one line,
// and the vector peaks over the scalar peak on a second, outside the per-scheme table.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <variant>

#include "experiments/io/scene_reader.hpp"
#include "integrators/ensemble/ensemble.hpp"
#include "integrators/schemes/moser_veselov_preprocessed.hpp"
#include "integrators/system/model.hpp"

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

#if defined(__x86_64__)
// One round of limits/vector_peak: vaddpd on registers 0–6 and vmulpd on 7–13,
// with register 14 = 0 and 15 = 1 (R is the register prefix: "xmm", "ymm", "zmm").
#define LGI_PEAK_PAIR(R, a, m) \
  "vaddpd %%" R "14, %%" R #a ", %%" R #a "\n\t vmulpd %%" R "15, %%" R #m ", %%" R #m "\n\t"
#define LGI_PEAK_ROUND(R)                                                                                    \
  LGI_PEAK_PAIR(R, 0, 7) LGI_PEAK_PAIR(R, 1, 8) LGI_PEAK_PAIR(R, 2, 9) LGI_PEAK_PAIR(R, 3, 10)               \
  LGI_PEAK_PAIR(R, 4, 11) LGI_PEAK_PAIR(R, 5, 12) LGI_PEAK_PAIR(R, 6, 13)
#define LGI_PEAK_SET(R, i) "vmovapd %%" R "15, %%" R #i "\n\t"
#define LGI_PEAK_LOOP(R, ZERO, ONE)                                                                          \
  asm volatile(ZERO ONE " %1, %%" R "15\n\t" LGI_PEAK_SET(R, 0) LGI_PEAK_SET(R, 1)                           \
               LGI_PEAK_SET(R, 2) LGI_PEAK_SET(R, 3) LGI_PEAK_SET(R, 4) LGI_PEAK_SET(R, 5)                   \
               LGI_PEAK_SET(R, 6) LGI_PEAK_SET(R, 7) LGI_PEAK_SET(R, 8) LGI_PEAK_SET(R, 9)                   \
               LGI_PEAK_SET(R, 10) LGI_PEAK_SET(R, 11) LGI_PEAK_SET(R, 12) LGI_PEAK_SET(R, 13)               \
               "mov %0, %%rcx\n\t"                                                                           \
               "1:\n\t" LGI_PEAK_ROUND(R) "dec %%rcx\n\t"                                                    \
               "jnz 1b\n\t"                                                                                  \
               "vzeroupper\n\t"                                                                              \
               :                                                                                             \
               : "r"(rounds), "m"(one)                                                                       \
               : "rcx", "xmm0", "xmm1", "xmm2", "xmm3", "xmm4", "xmm5", "xmm6", "xmm7", "xmm8", "xmm9",      \
                 "xmm10", "xmm11", "xmm12", "xmm13", "xmm14", "xmm15", "cc")
#endif

// The packed version of scalar_peak on `isa`'s widest registers (registered
// only where the CPU has the instruction set).
void vector_peak(benchmark::State& state, integrators::ensemble::Isa isa) {
#if defined(__x86_64__)
  using integrators::ensemble::Isa;
  constexpr std::int64_t rounds = 1 << 16;
  static const double one = 1.0;
  const int lanes = isa == Isa::avx512 ? 8 : isa == Isa::avx2 ? 4 : 2;
  for (auto _ : state) {
    if (isa == Isa::avx512) {
      LGI_PEAK_LOOP("zmm", "vpxorq %%zmm14, %%zmm14, %%zmm14\n\t", "vbroadcastsd");
    } else if (isa == Isa::avx2) {
      LGI_PEAK_LOOP("ymm", "vxorpd %%ymm14, %%ymm14, %%ymm14\n\t", "vbroadcastsd");
    } else {
      LGI_PEAK_LOOP("xmm", "vxorpd %%xmm14, %%xmm14, %%xmm14\n\t", "vmovddup");
    }
  }
  state.counters["lane_flops_per_ns"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * static_cast<double>(rounds) * 14.0 * lanes * 1e-9,
                         benchmark::Counter::kIsRate);
#else
  (void)isa;
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
        if (!scheme[j].step_keeping_attitude(body, x[j], k * h, h, work).converged) failed = true;
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

enum class Attitude { matrix, quaternion, quaternion_and_matrix };

// 2048 updates with f near Hairer & Vilmart's body's at h = 0.01 (|f| ≈ 0.01).
template <Attitude A>
void dmv_update(benchmark::State& state) {
  constexpr int steps = 2048;
  for (auto _ : state) {
    system::State x{lie::Mat3::Identity(), lie::Vec3(1.8, 0.4, -0.9)};
    integrators::moser_veselov::Carry carry;
    integrators::moser_veselov::CayleyQuaternion q;
    for (int k = 0; k < steps; ++k) {
      const lie::Vec3 f(0.009, 0.0025 + 1e-12 * (k & 7), -0.0045);
      if constexpr (A == Attitude::matrix) {
        integrators::moser_veselov::apply_cayley_step(f, x, carry);
      } else {
        integrators::moser_veselov::apply_cayley_step(f, x, carry, q);
        if constexpr (A == Attitude::quaternion_and_matrix) q.write(x.R);
      }
      // The state is in memory after every step, as the time loop's is.
      benchmark::DoNotOptimize(x);
      benchmark::DoNotOptimize(q);
    }
  }
  state.counters["ns_per_step"] = benchmark::Counter(static_cast<double>(state.iterations()) * steps * 1e-9,
                                                     benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK(scalar_peak)->Name("limits/scalar_peak");
// Every form uses VEX encodings (AVX), so all are registered only where the CPU has AVX2.
[[maybe_unused]] const bool vector_peaks_registered = [] {
  using integrators::ensemble::Isa;
  const auto isas = integrators::ensemble::available_isas();
  if (std::find(isas.begin(), isas.end(), Isa::avx2) == isas.end()) return false;
  for (const Isa isa : isas)
    benchmark::RegisterBenchmark((std::string("limits/vector_peak/") + integrators::ensemble::isa_name(isa)).c_str(),
                                 vector_peak, isa);
  return true;
}();
BENCHMARK(dmv_pre10_steps<1>)->Name("limits/dmv-pre10/one");
BENCHMARK(dmv_pre10_steps<2>)->Name("limits/dmv-pre10/two_interleaved");
BENCHMARK(dmv_update<Attitude::matrix>)->Name("limits/dmv-update/matrix");
BENCHMARK(dmv_update<Attitude::quaternion>)->Name("limits/dmv-update/quaternion");
BENCHMARK(dmv_update<Attitude::quaternion_and_matrix>)->Name("limits/dmv-update/quaternion_and_matrix");

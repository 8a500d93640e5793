#pragma once
// Storage of an ensemble of tangent flows (docs/ensemble.md, "Tangent flows
// in lanes"): the state (R, Π) and up to six tangent vectors v = (ξ, δΠ) of
// each lane, and the running sums of the chaos indicators of each lane
// (integrators/core/tangent_flow.hpp, ChaosAccumulator). Plain numbers, as
// ensemble_model.hpp: the kernels are compiled once per instruction set.
#include <cstdint>

#include "integrators/ensemble/ensemble_model.hpp"

namespace lgi::integrators::ensemble {

/// Rows 0 … 11 as LaneBlock (R(0,0), R(0,1), …, R(2,2), Π1, Π2, Π3); then
/// vector k's six components (ξ1 ξ2 ξ3 δΠ1 δΠ2 δΠ3) at rows 12 + 6k … 17 + 6k.
inline constexpr int max_tangent_vectors = 6;
inline constexpr int tangent_rows = state_rows + 6 * max_tangent_vectors;
inline constexpr int tangent_row(int vector, int component) { return state_rows + 6 * vector + component; }
struct alignas(64) TangentBlock {
  double row[tangent_rows][max_lanes];
};

/// The chaos indicators' loop (accumulate_chaos_indicators) of every lane of
/// an ensemble with one tangent vector: the grid's time, the lanes' sums of
/// ChaosAccumulator, and which lanes are still running. The kernel advances
/// it by up to a given number of steps; the stepper reads the stop flag in
/// between (no atomic in a kernel unit).
struct alignas(64) ChaosLanes {
  double log_sum[max_lanes] = {}, weighted[max_lanes] = {}, mean_sum[max_lanes] = {}, y[max_lanes] = {};
  double marked_log_sum[max_lanes] = {};
  double running[max_lanes] = {};  // 1: running; 0: padding, or blown up (its values NaN)
  double steps[max_lanes] = {};    // the steps each lane completed (whole numbers)
  double t = 0.0, s = 0.0, marked_s = 0.0;
  bool marked = false;
  std::int64_t grid_steps = 0;  // the steps taken on the grid
};

/// One step of the state and the first `vectors` tangent vectors of every
/// lane (tangent_kernel.hpp) from t to t + h.
using TangentStepKernel = void (*)(const EnsembleModel& model, TangentBlock& block, double t, double h);
/// Up to max_steps steps of the indicators' loop from c.t towards t_end (steps dt),
/// on the state and vector 0 of every lane; ends early where no lane runs.
using ChaosKernel = void (*)(const EnsembleModel& model, TangentBlock& block, ChaosLanes& c, double t0,
                             double t_end, double dt, std::int64_t max_steps);

/// The tangent kernels compiled for one instruction set (KernelSet's lanes).
struct TangentKernelSet {
  int lanes = 0;
  TangentStepKernel step_one = nullptr;  // one tangent vector (MEGNO, λ)
  TangentStepKernel step_six = nullptr;  // six (GALI, the spectrum)
  ChaosKernel chaos = nullptr;
};

// One per instruction set (ensemble_<isa>.cpp); call only where the CPU has it.
TangentKernelSet baseline_tangent_kernels();
TangentKernelSet avx2_tangent_kernels();
TangentKernelSet avx512_tangent_kernels();

}  // namespace lgi::integrators::ensemble

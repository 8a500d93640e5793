#pragma once
// The Cardan top's tangent flow in lanes (docs/ensemble.md, "Cardan tangent
// flows"): the kernels' view of a CardanTop (plain numbers, as
// ensemble_model.hpp: the kernels are compiled once per instruction set)
// and the kernels' signatures. The lanes live in a TangentBlock
// (tangent_block.hpp): rows 0 … 5 hold x = (q1, q2, q3, p1, p2, p3), the
// tangent rows hold the vectors v ∈ ℝ⁶ as they hold (ξ, δΠ) on SO(3).
#include <cstdint>

#include "integrators/ensemble/tangent_block.hpp"

namespace lgi::integrators::ensemble {

/// CardanTop (integrators/system/cardan.hpp) as cardan_tangent_kernel.hpp reads it.
struct CardanLaneModel {
  double J[3][3] = {};                // the body's inertia about the fixed point (symmetric)
  double inner[3] = {};               // the inner ring's (A_i, B_i, C_i)
  double outer = 0.0;                 // C_o
  double gamma[3] = {0.0, 0.0, 1.0};  // Ry(α)ᵀ e3: the vertical in the pedestal frame
  double body[3] = {};                // g m χ
  double inner_moment[3] = {};        // g m_i c_i
  double outer_moment[3] = {};        // g m_o c_o
  bool potential = false;             // g ≠ 0: V enters the field
  bool tilted = false;                // γ ≠ e3: V depends on q1 (its cos and sin are needed)
};

inline constexpr int cardan_state_rows = 6;

/// One RK4 step of x and the first `vectors` tangent vectors of every lane.
using CardanStepKernel = void (*)(const CardanLaneModel& model, TangentBlock& block, double h);
/// Up to max_steps steps of the indicators' loop, as ChaosKernel (tangent_block.hpp).
using CardanChaosKernel = void (*)(const CardanLaneModel& model, TangentBlock& block, ChaosLanes& c, double t0,
                                   double t_end, double dt, std::int64_t max_steps);

struct CardanTangentKernelSet {
  int lanes = 0;
  CardanStepKernel step_one = nullptr;
  CardanStepKernel step_six = nullptr;
  CardanChaosKernel chaos = nullptr;
};

// One per instruction set (ensemble_<isa>.cpp); call only where the CPU has it.
CardanTangentKernelSet baseline_cardan_tangent_kernels();
CardanTangentKernelSet avx2_cardan_tangent_kernels();
CardanTangentKernelSet avx512_cardan_tangent_kernels();

}  // namespace lgi::integrators::ensemble

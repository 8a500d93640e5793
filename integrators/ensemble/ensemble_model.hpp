#pragma once
// The model an ensemble kernel steps (docs/ensemble.md), as plain numbers:
// no Eigen and no xsimd here, since the kernels are compiled once per
// instruction set (ensemble_avx2.cpp, ...) and must share no inline code
// with the rest of lgi. ensemble.cpp fills it from a system model.
//
// It mirrors system::FreeBody and system::SceneModel (system/model.hpp)
// with the terms an ensemble kernel can evaluate in lanes: gravity, the
// harmonic drive and the magnetic dipole. The spring (a matrix logarithm
// per lane) has no kernel: a scene that declares it runs one trajectory at
// a time. Row-major 3×3 arrays: J_inv[i][j] = J⁻¹(i, j).
namespace lgi::integrators::ensemble {

struct EnsembleModel {
  double J_inv[3][3] = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
  /// system::FreeBody: no torque at all, Π̇ = Π × Ω (the stage attitudes are never formed).
  bool free_body = true;
  // system::SceneModel: the terms of system/terms/scene_terms.hpp in their
  // order (gravity, spring, drive, magnetic), each summed even when it is
  // not declared (an exact zero), as the scene model's fold does.
  bool gravity = false;
  double mg_chi[3] = {0.0, 0.0, 0.0};  // m g χ (terms/gravity.hpp)
  bool drive = false;
  double drive_amplitude[3] = {0.0, 0.0, 0.0};  // A (terms/harmonic_drive.hpp)
  double drive_frequency = 0.0, drive_phase = 0.0;
  bool magnetic = false;
  double magnetic_field[3] = {0.0, 0.0, 0.0};         // B, space frame (terms/magnetic_dipole.hpp)
  double magnetic_minus_moment[3] = {0.0, 0.0, 0.0};  // −μ
};

/// Storage of one ensemble: 12 rows (R(0,0), R(0,1), …, R(2,2), Π1, Π2, Π3)
/// of max_lanes doubles each, aligned for the widest vector.
inline constexpr int max_lanes = 16;
inline constexpr int state_rows = 12;
struct alignas(64) LaneBlock {
  double row[state_rows][max_lanes];
};

/// One step of every lane of `block` from t to t + h (the kernels of one
/// instruction set; `lanes` is that set's lane count).
using StepKernel = void (*)(const EnsembleModel& model, LaneBlock& block, double t, double h);

/// The kernels compiled for one instruction set.
struct KernelSet {
  const char* isa = "";  // "sse2", "avx2", "avx512"
  int lanes = 0;
  StepKernel rkmk4 = nullptr;
};

// One per instruction set (ensemble_<isa>.cpp); call only where the CPU has it.
KernelSet baseline_kernels();
KernelSet avx2_kernels();
KernelSet avx512_kernels();

}  // namespace lgi::integrators::ensemble

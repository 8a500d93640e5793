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
  // The DMV schemes (dmv_kernel.hpp): for dmv-pre*, the degree of the
  // modified-inertia series in h² (moser_veselov_series.hpp); for dmv and
  // lgvi, no series (preprocessed = false) and the moments J_ii themselves.
  bool preprocessed = true;
  int series_degrees = 0;
  double moments[3] = {1.0, 1.0, 1.0};
};

/// Storage of one ensemble: 12 rows (R(0,0), R(0,1), …, R(2,2), Π1, Π2, Π3)
/// of max_lanes doubles each, aligned for the widest vector.
inline constexpr int max_lanes = 16;
inline constexpr int state_rows = 12;
struct alignas(64) LaneBlock {
  double row[state_rows][max_lanes];
};

/// What a scheme carries from step to step, per lane (schemes with memory:
/// the DMV family, dmv_kernel.hpp). Rows 0 … 31 are the scalar scheme's
/// memory in its checkpoint layout (moser_veselov::StepMemory::save: the
/// carries of Π and of R, column-major, the predictor's count, its h and its
/// six Cayley parameters over their step lengths, newest first), so that a lane's memory passes to
/// and from the scalar scheme as one copy; then the lane's per-run constants
/// (the series in h² of css and cdd, DmvPreprocessed::free_body_series), and
/// the kernel's verdict per lane.
namespace dmv_rows {
inline constexpr int carry_Pi = 0;   // 3 rows
inline constexpr int carry_R = 3;    // 9 rows: carry.R(i, j) at carry_R + i + 3 j (dmv, lgvi)
// The preprocessed schemes keep a free body's attitude as a quaternion
// (DmvPreprocessed::save_memory) in R's carry's rows: q (w, x, y, z), its carry.
inline constexpr int quaternion = 3;        // 4 rows
inline constexpr int quaternion_carry = 7;  // 4 rows
inline constexpr int count = 12;     // the predictor's valid entries
inline constexpr int step = 13;      // the step length of its history
inline constexpr int history = 14;   // 18 rows: w_{k−m}/h_{k−m} component i at history + 3 m + i (w = J f)
inline constexpr int memory = 32;    // rows 0 … 31: the scalar scheme's memory
inline constexpr int css = 32;       // 4 rows: css in h², lowest degree first
inline constexpr int cdd = 36;       // 4 rows
inline constexpr int stepped = 40;   // 1 where the kernel took the step, 0 where the scalar scheme must
inline constexpr int active = 41;    // 1 for a lane in use (EnsembleStepper::set_active), 0 for padding or a finished run
// The kernel's table of modified moments by step length (as MomentsByStep in
// moser_veselov.hpp: the h of a fixed-step run differ in their last bits):
// per entry μ = 1/Ĩ, 2μ, d (3 rows each), 1 where μ > 0, and the Newton bound c.
inline constexpr int moments = 42;
inline constexpr int moment_rows = 11;
inline constexpr int moment_entries = 8;
inline constexpr int rows = moments + moment_rows * moment_entries;
}  // namespace dmv_rows
struct alignas(64) LaneMemory {
  double row[dmv_rows::rows][max_lanes];
  double moments_h[dmv_rows::moment_entries];  // the h of each entry; NaN: empty (equal to no h)
};

/// One step of every lane of `block` from t to t + h (the kernels of one
/// instruction set; `lanes` is that set's lane count). A kernel of a scheme
/// with memory reads and writes `memory` and may leave a lane to the scalar
/// scheme (dmv_rows::stepped); the others read only its active row. Returns
/// whether every active lane (dmv_rows::active) was stepped by the kernel and
/// is finite (detail::finite_state), the common case, in which the stepper
/// reads no flag lane by lane.
using StepKernel = bool (*)(const EnsembleModel& model, LaneBlock& block, LaneMemory& memory, double t, double h);

/// The kernels compiled for one instruction set.
struct KernelSet {
  const char* isa = "";  // "sse2", "avx2", "avx512"
  int lanes = 0;
  StepKernel rkmk4 = nullptr;
  StepKernel dmv_pre = nullptr;  // dmv, lgvi, dmv-pre4 … dmv-pre10 on a free body with diagonal J
};

// One per instruction set (ensemble_<isa>.cpp); call only where the CPU has it.
KernelSet baseline_kernels();
KernelSet avx2_kernels();
KernelSet avx512_kernels();

}  // namespace lgi::integrators::ensemble

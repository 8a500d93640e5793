#pragma once
// The ensemble stepper: several trajectories of one scene advanced together
// in SIMD lanes, each lane bit for bit the trajectory the scalar scheme
// computes one at a time (docs/ensemble.md). Which schemes have a kernel is
// stated in their facts (SchemeFacts::lane_kernel) and read here from the
// one registry (SchemeInfo::lanes); the ensemble keeps no list of names.
// Kernels exist for rkmk4 on the free body and on scenes whose torques are
// gravity, the harmonic drive and the magnetic dipole (not the spring), and
// for dmv, lgvi and dmv-pre4 … dmv-pre10 on a free body with diagonal J
// (with the scalar scheme behind each lane for the steps the kernel leaves,
// lane_fallback.hpp); they are compiled for the baseline instruction set
// (SSE2 on x86-64) and, on x86-64, for AVX2 and AVX-512F (without FMA),
// chosen at run time from what the CPU supports. The tangent flow of rkmk4
// and the chaos indicators' loop have lanes of their own
// (tangent_ensemble.hpp).
//
// A step allocates nothing: the lanes live in a fixed-size block inside the
// stepper. Lanes beyond the trajectories in use are padding (a copy of the
// first trajectory) whose results are dropped.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "integrators/ensemble/ensemble_model.hpp"
#include "integrators/ensemble/lane_fallback.hpp"
#include "integrators/ensemble/lane_mode.hpp"
#include "integrators/system/model.hpp"

namespace lgi::integrators {
struct SchemeInfo;  // registry.hpp
}

namespace lgi::integrators::ensemble {

using system::State;

/// The instruction sets the kernels are compiled for, narrowest first.
enum class Isa { baseline, avx2, avx512 };

/// "sse2" (the baseline on x86-64; xsimd's name for it elsewhere), "avx2", "avx512".
const char* isa_name(Isa isa);
/// The name's instruction set, or nullopt for an unknown name.
std::optional<Isa> parse_isa(std::string_view name);
/// Compiled in, and supported by this CPU and operating system.
bool isa_available(Isa isa);
/// The available instruction sets, narrowest first (the baseline always).
std::vector<Isa> available_isas();
/// The widest available instruction set.
Isa best_isa();
/// Trajectories per ensemble step on that instruction set.
int isa_lanes(Isa isa);

/// The instruction set sweeps use for their ensemble path, or nullopt for
/// none (one trajectory at a time). Default: best_isa(). `lgi sweep --simd`
/// sets it once, before the run starts.
std::optional<Isa> sweep_isa();
void set_sweep_isa(std::optional<Isa> isa);

/// Whether the scheme's facts declare a lane kernel (SchemeInfo::lanes).
bool has_kernel(const SchemeInfo& scheme);
/// The same for a registry name; false for a name the registry does not know.
bool has_kernel(std::string_view scheme);
/// Empty if the scheme runs in lanes on this model, else why not: the
/// registry's refusal of the scene (integrators::unsupported_reason), no lane
/// kernel, or what the kernel cannot evaluate. Call it qualified: the
/// registry's function of the same signature is found by ADL.
std::string unsupported_reason(const SchemeInfo& scheme, const system::AnyModel& model);
/// The same for a registry name (find_scheme); an unknown name gets
/// "unknown scheme 'NAME' (lgi schemes lists them)".
std::string unsupported_reason(std::string_view scheme, const system::AnyModel& model);

class EnsembleStepper {
 public:
  /// nullopt unless unsupported_reason(scheme, model) is empty and isa is available.
  static std::optional<EnsembleStepper> make(const SchemeInfo& scheme, const system::AnyModel& model, Isa isa);
  /// make() for the registry's scheme of that name; nullopt for an unknown name.
  static std::optional<EnsembleStepper> make(std::string_view scheme, const system::AnyModel& model, Isa isa);

  int lanes() const { return lanes_; }
  Isa isa() const { return isa_; }
  /// The scheme's registry name.
  std::string_view scheme() const { return scheme_; }
  /// The ensemble loop with the scheme's scalar hooks (its registry entry's LaneMode::run; run_ensemble).
  RunLanes run_lanes() const { return run_lanes_; }
  /// Right-hand-side evaluations one step costs per lane (WorkCounters), for
  /// a scheme without memory; with memory, see outcome().
  int rhs_per_step() const { return rhs_per_step_; }
  /// Whether the scheme carries memory from step to step (then each lane has
  /// a scalar scheme behind it: start_lane(), outcome(), step_lane_from()).
  bool has_memory() const { return fallback_ != nullptr; }
  /// Sets a lane's state (and makes it active).
  void set_lane(int lane, const State& s);
  void get_lane(int lane, State& s) const;
  /// set_lane and, for a scheme with memory, the scheme's start() for the lane.
  StepStatus start_lane(int lane, const State& s, double t0);
  /// An inactive lane is still stepped by the kernel but never by the scalar scheme.
  void set_active(int lane, bool active);
  /// Every lane from t to t + h (for a scheme with memory, the lanes the
  /// kernel leaves by the scalar scheme, with retry_halving as the run's).
  /// Returns whether the kernel took every active lane's step and every
  /// active lane is finite (the common case: then kernel_stepped and
  /// lane_finite are true for every lane, and the loop need not ask them).
  bool step(double t, double h, int retry_halving = 0);
  /// With memory: the lane steps the kernel has taken (active lanes), all runs.
  std::int64_t kernel_lane_steps() const { return kernel_lane_steps_; }
  /// With memory: the last step of an active lane (its status and work counters).
  const LaneOutcome& outcome(int lane) const;
  /// With memory: whether the kernel took the lane's last step (outcome(): one
  /// Newton correction, rhs_per_step() evaluations).
  bool kernel_stepped(int lane) const { return kernel_stepped_[lane]; }
  /// With memory: the lane's memory (dmv_rows::memory values), and a step of
  /// the lane's scalar scheme from x with such a snapshot (event location).
  void save_lane_memory(int lane, std::span<double> out) const;
  bool step_lane_from(int lane, std::span<const double> snapshot, State& x, double t, double h, int retry_halving,
                      WorkCounters& work);
  /// After step(): whether every entry of lane's R and Π is finite (detail::finite_state).
  bool lane_finite(int lane) const { return finite_[lane]; }

 private:
  EnsembleStepper() = default;
  int active_count() const;
  EnsembleModel model_{};
  StepKernel kernel_ = nullptr;
  RunLanes run_lanes_ = nullptr;
  std::string scheme_;
  int lanes_ = 0;
  int rhs_per_step_ = 0;
  Isa isa_ = Isa::baseline;
  LaneBlock block_{};
  LaneMemory memory_{};
  std::unique_ptr<LaneFallback> fallback_;
  LaneOutcome outcome_[max_lanes];
  bool active_[max_lanes] = {};
  bool kernel_stepped_[max_lanes] = {};
  bool finite_[max_lanes] = {};
  std::int64_t kernel_lane_steps_ = 0;
};

}  // namespace lgi::integrators::ensemble

#pragma once
// Tangent flows in SIMD lanes (docs/ensemble.md, "Tangent flows in lanes"):
// the state and one or six tangent vectors of several trajectories of one
// scene stepped together by RKMK4 (tangent_kernel.hpp), and the chaos
// indicators' loop (λ, MEGNO) run in the lanes (chaos_kernel.hpp).
//
// Models with a kernel: the free body, and scenes whose torques are gravity,
// the harmonic drive and the magnetic dipole (as rkmk4's state kernel; not
// the spring). For those, scalar_tangent_step is the scalar step, the lane
// template on double, and every lane is bit for bit that step; a spring
// scene steps with integrators/core/tangent_flow.hpp's Eigen form.
// with_tangent_step picks the one for a model: the chaos indicators
// (`lgi indicators`, `lgi chaos-map`, `lgi poincare --lyapunov`) step with it.
#include <atomic>
#include <optional>
#include <span>
#include <variant>

#include "integrators/ensemble/ensemble.hpp"
#include "integrators/ensemble/tangent_block.hpp"
#include "integrators/system/model.hpp"
#include "integrators/core/tangent_flow.hpp"

namespace lgi::integrators::ensemble {

/// The kernels' view of a model (ensemble_model.hpp), or nullopt where none
/// applies (a spring; why says so).
std::optional<EnsembleModel> ensemble_model(const system::AnyModel& model, std::string* why = nullptr);

/// One RKMK4 step of the state and its tangent vector(s) (tangent_kernel.hpp
/// on double): the scalar step the lanes reproduce.
void scalar_tangent_step(const EnsembleModel& model, State& x, Vec6& v, double t, double h);
void scalar_tangent_step(const EnsembleModel& model, State& x, Mat6& V, double t, double h);

/// f(step) with step(x, v, t, h) the model's tangent step: scalar_tangent_step
/// where the model has a kernel, else integrators::tangent_step.
template <class F>
auto with_tangent_step(const system::AnyModel& model, F&& f) {
  if (const std::optional<EnsembleModel> m = ensemble_model(model))
    return f([m = *m](State& x, auto& v, double t, double h) { scalar_tangent_step(m, x, v, t, h); });
  return std::visit(
      [&](const auto& alt) {
        return f([&alt](State& x, auto& v, double t, double h) { integrators::tangent_step(alt, x, v, t, h); });
      },
      model);
}

/// The driver of a chaos kernel (ChaosKernel, CardanChaosKernel): calls
/// run_256_steps until the lanes 0 … n − 1 reach t_end or all stopped
/// running, reading `stop` every 256 steps as the scalar loop does; true
/// where the flag ended the run.
template <class Run>
bool run_chaos_lanes(ChaosLanes& c, int n, double t_end, const std::atomic<bool>* stop, Run&& run_256_steps) {
  while (c.t < t_end) {
    run_256_steps(c);
    if (stop != nullptr && c.grid_steps % 256 == 0 && stop->load(std::memory_order_relaxed)) return true;
    bool any_running = false;
    for (int l = 0; l < n; ++l) any_running = any_running || c.running[l] != 0.0;
    if (!any_running) break;
  }
  return false;
}
/// ChaosAccumulator's values for lanes 0 … out.size() − 1 of a finished run (NaN where not ok).
void chaos_lane_results(const ChaosLanes& c, bool stopped, std::span<ChaosIndicators> out);

/// The tangent kernels of an available instruction set (ensemble.cpp).
TangentKernelSet tangent_kernels(Isa isa);

/// The start of a chaos_indicators() call in lanes (TangentEnsemble and
/// CardanTangentEnsemble): clears `out`; false if there is nothing to run (no
/// orbit, or a grid t0 + k dt that cannot reach t_end: then every result is
/// marked failed with NaN values, as accumulate_chaos_indicators does).
bool begin_chaos_outputs(std::span<ChaosIndicators> out, double t0, double t_end, double dt);

class TangentEnsemble {
 public:
  /// nullopt unless the model has a kernel, isa is available and vectors is 1 or 6.
  static std::optional<TangentEnsemble> make(const system::AnyModel& model, Isa isa, int vectors = 1);

  int lanes() const { return lanes_; }
  int vectors() const { return vectors_; }
  Isa isa() const { return isa_; }
  /// A lane's state and vector(s): Vec6 with one vector, Mat6 (the columns) with six.
  void set_lane(int lane, const State& s, const Vec6& v);
  void set_lane(int lane, const State& s, const Mat6& V);
  void get_lane(int lane, State& s, Vec6& v) const;
  void get_lane(int lane, State& s, Mat6& V) const;
  /// Every lane from t to t + h: each lane's scalar_tangent_step, bit for bit.
  void step(double t, double h);
  /// With one vector: chaos_indicators (tangent_flow.hpp) of lanes 0 … out.size() − 1,
  /// bit for bit, from their set_lane states over [t0, t_end] with steps dt (the other
  /// lanes are padding). The lanes end at t_end (a lane that blew up: anywhere).
  void chaos_indicators(double t0, double t_end, double dt, const std::atomic<bool>* stop,
                        std::span<ChaosIndicators> out);

 private:
  TangentEnsemble() = default;
  EnsembleModel model_{};
  TangentKernelSet kernels_{};
  Isa isa_ = Isa::baseline;
  int lanes_ = 0, vectors_ = 1;
  TangentBlock block_{};
  ChaosLanes chaos_{};
};

}  // namespace lgi::integrators::ensemble

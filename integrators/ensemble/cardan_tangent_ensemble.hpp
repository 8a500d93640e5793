#pragma once
// The Cardan top's tangent flow in SIMD lanes (docs/ensemble.md, "Cardan
// tangent flows"): the state x = (q, p) ∈ T³ × ℝ³ and one or six tangent
// vectors of several orbits of one CardanTop stepped together by RK4
// (cardan_tangent_kernel.hpp), and the chaos indicators' loop (λ, MEGNO) in
// the lanes. scalar_cardan_tangent_step is the kernel on double: the scalar
// step of `lgi chaos-map` and `lgi indicators` on Cardan scenes, and every
// lane is that step bit for bit. It agrees with torus_tangent_flow.hpp's
// Eigen and dual-number form to round-off (not bit for bit: the operations
// are ordered differently; tests/test_ensemble_cardan.cpp).
#include <atomic>
#include <optional>
#include <span>

#include "integrators/ensemble/cardan_tangent_block.hpp"
#include "integrators/ensemble/ensemble.hpp"
#include "integrators/system/cardan.hpp"
#include "integrators/core/tangent_flow.hpp"

namespace lgi::integrators::ensemble {

/// The kernels' view of a Cardan top.
CardanLaneModel cardan_lane_model(const system::CardanTop& top);

/// One RK4 step of x = (q, p) and its tangent vector(s) (the kernel on double).
void scalar_cardan_tangent_step(const CardanLaneModel& model, system::Vec6& x, Vec6& v, double h);
void scalar_cardan_tangent_step(const CardanLaneModel& model, system::Vec6& x, Mat6& V, double h);

/// λ and ⟨Y⟩ of one orbit over [0, t_end], steps dt: accumulate_chaos_indicators
/// with scalar_cardan_tangent_step (NaN where x or v blew up or `stop` ended it).
/// x ends at t_end.
ChaosIndicators scalar_cardan_chaos_indicators(const CardanLaneModel& model, system::Vec6& x, Vec6 v, double t_end,
                                               double dt, const std::atomic<bool>* stop = nullptr);

CardanTangentKernelSet cardan_tangent_kernels(Isa isa);

class CardanTangentEnsemble {
 public:
  /// nullopt unless isa is available and vectors is 1 or 6.
  static std::optional<CardanTangentEnsemble> make(const system::CardanTop& top, Isa isa, int vectors = 1);

  int lanes() const { return lanes_; }
  Isa isa() const { return isa_; }
  void set_lane(int lane, const system::Vec6& x, const Vec6& v);
  void set_lane(int lane, const system::Vec6& x, const Mat6& V);
  void get_lane(int lane, system::Vec6& x, Vec6& v) const;
  void get_lane(int lane, system::Vec6& x, Mat6& V) const;
  /// Every lane by h: each lane's scalar_cardan_tangent_step, bit for bit.
  void step(double h);
  /// With one vector: scalar_cardan_chaos_indicators of lanes 0 … out.size() − 1,
  /// bit for bit, from their set_lane states over [t0, t_end] (the other lanes are padding).
  void chaos_indicators(double t0, double t_end, double dt, const std::atomic<bool>* stop,
                        std::span<ChaosIndicators> out);

 private:
  CardanTangentEnsemble() = default;
  CardanLaneModel model_{};
  CardanTangentKernelSet kernels_{};
  Isa isa_ = Isa::baseline;
  int lanes_ = 0, vectors_ = 1;
  TangentBlock block_{};
  ChaosLanes chaos_{};
};

}  // namespace lgi::integrators::ensemble

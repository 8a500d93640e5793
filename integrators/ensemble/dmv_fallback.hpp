#pragma once
// The scalar DMV scheme behind the lanes of dmv_kernel.hpp (lane_fallback.hpp)
// for any scheme of the family whose facts declare LaneKernel::dmv_diagonal
// (dmv, lgvi, the preprocessed dmv-pre4 … dmv-pre10): the registry makes it
// from the scheme's type (lane_mode_of.hpp). A preprocessed scheme (one with
// css_in_h2() and series_degrees) gives the kernel its series in h²; the
// others, the moments J_ii (moser_veselov::DiagonalInertia).
#include <array>
#include <limits>
#include <memory>
#include <vector>

#include "integrators/ensemble/lane_fallback.hpp"
#include "integrators/core/loop_support.hpp"

namespace lgi::integrators::ensemble {

namespace dmv_fallback_detail {

namespace scalar = integrators::detail;  // the scalar loop's helpers (loop_support.hpp)

template <class Scheme>
class DmvFallback final : public LaneFallback {
 public:

  explicit DmvFallback(const system::FreeBody& model) : model_(model) { buffer_.reserve(dmv_rows::memory); }

  StepStatus start(int lane, const State& s, double t0, LaneMemory& memory) override {
    Scheme& scheme = schemes_[static_cast<std::size_t>(lane)];
    scheme = Scheme{};
    const StepStatus st = scalar::start(scheme, model_, s, t0);
    save(lane, memory);
    // The lane's constants change: the kernel's table of moments starts empty.
    for (double& key : memory.moments_h) key = std::numeric_limits<double>::quiet_NaN();
    if constexpr (requires { scheme.css_in_h2(); }) {  // the preprocessed schemes' series
      for (std::size_t k = 0; k < 4; ++k) {
        memory.row[dmv_rows::css + static_cast<int>(k)][lane] = scheme.css_in_h2()[k];
        memory.row[dmv_rows::cdd + static_cast<int>(k)][lane] = scheme.cdd_in_h2()[k];
      }
    }
    return st;
  }

  void step(int lane, LaneBlock& block, LaneMemory& memory, double t, double h, int retry_halving,
            LaneOutcome& out) override {
    Scheme& scheme = schemes_[static_cast<std::size_t>(lane)];
    restore(lane, memory, scheme);
    State x;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) x.R(i, j) = block.row[3 * i + j][lane];
      x.Pi(i) = block.row[9 + i][lane];
    }
    out.work = {};
    // The loop's step (detail::loop_step): the preprocessed schemes keep the
    // attitude in the lane's memory (dmv_rows::quaternion), and x.R is left.
    out.status = retry_halving > 0 ? scalar::step_with_halving(scheme, model_, x, t, h, retry_halving, out.work)
                                   : scalar::recorded_step(scheme, model_, x, t, h, out.work);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) block.row[3 * i + j][lane] = x.R(i, j);
      block.row[9 + i][lane] = x.Pi(i);
    }
    save(lane, memory);
  }

  bool step_from(int lane, std::span<const double> snapshot, State& x, double t, double h, int retry_halving,
                 WorkCounters& work) override {
    Scheme copy = schemes_[static_cast<std::size_t>(lane)];
    if (!copy.restore_memory(snapshot)) return false;
    const bool stepped = retry_halving > 0
                             ? scalar::step_with_halving(copy, model_, x, t, h, retry_halving, work).converged
                             : scalar::loop_step(copy, model_, x, t, h, work).converged;
    if constexpr (scalar::keeps_attitude<Scheme, system::FreeBody>) copy.write_attitude(x);  // R(q), as the loop's
    return stepped;
  }

 private:
  void save(int lane, LaneMemory& memory) {
    buffer_.clear();
    schemes_[static_cast<std::size_t>(lane)].save_memory(buffer_);
    for (int r = 0; r < dmv_rows::memory; ++r) memory.row[r][lane] = buffer_[static_cast<std::size_t>(r)];
  }
  void restore(int lane, const LaneMemory& memory, Scheme& scheme) {
    buffer_.resize(dmv_rows::memory);
    for (int r = 0; r < dmv_rows::memory; ++r) buffer_[static_cast<std::size_t>(r)] = memory.row[r][lane];
    [[maybe_unused]] const bool restored = scheme.restore_memory(buffer_);  // the rows hold what save() wrote
  }

  system::FreeBody model_;
  std::array<Scheme, max_lanes> schemes_{};
  std::vector<double> buffer_;  // one lane's memory, reserved once: a step allocates nothing
};

}  // namespace dmv_fallback_detail

/// The lanes' scalar Scheme on a free body (LaneFallbackFactory); sets the kernel's constants.
template <class Scheme>
std::unique_ptr<LaneFallback> make_dmv_fallback(const system::FreeBody& model, EnsembleModel& constants) {
  if constexpr (requires { Scheme::series_degrees; }) {
    constants.preprocessed = true;
    constants.series_degrees = Scheme::series_degrees;
  } else {
    constants.preprocessed = false;
    for (int i = 0; i < 3; ++i) constants.moments[i] = model.inertia.J(i, i);
  }
  return std::make_unique<dmv_fallback_detail::DmvFallback<Scheme>>(model);
}

}  // namespace lgi::integrators::ensemble

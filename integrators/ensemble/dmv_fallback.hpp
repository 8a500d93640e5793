// The scalar DMV schemes behind the lanes of dmv_kernel.hpp (lane_fallback.hpp):
// dmv, lgvi and the preprocessed dmv-pre4 … dmv-pre10.
#include <array>
#include <limits>
#include <vector>

#include "integrators/ensemble/lane_fallback.hpp"
#include "integrators/loop_support.hpp"
#include "integrators/moser_veselov_preprocessed.hpp"

namespace lgi::integrators::ensemble {

namespace {

template <class Scheme>
class DmvFallback final : public LaneFallback {
 public:

  explicit DmvFallback(const system::FreeBody& model) : model_(model) { buffer_.reserve(dmv_rows::memory); }

  StepStatus start(int lane, const State& s, double t0, LaneMemory& memory) override {
    Scheme& scheme = schemes_[static_cast<std::size_t>(lane)];
    scheme = Scheme{};
    const StepStatus st = detail::start(scheme, model_, s, t0);
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
    out.status = retry_halving > 0 ? detail::step_with_halving(scheme, model_, x, t, h, retry_halving, out.work)
                                   : detail::recorded_step(scheme, model_, x, t, h, out.work);
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
                             ? detail::step_with_halving(copy, model_, x, t, h, retry_halving, work).converged
                             : detail::loop_step(copy, model_, x, t, h, work).converged;
    if constexpr (detail::keeps_attitude<Scheme, system::FreeBody>) copy.write_attitude(x);  // R(q), as the loop's
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

template <int Order>
std::unique_ptr<LaneFallback> make_for(const system::FreeBody& model, EnsembleModel& constants) {
  constants.preprocessed = true;
  constants.series_degrees = moser_veselov::ModifiedInertiaSeries<Order>::degrees;
  return std::make_unique<DmvFallback<DmvPreprocessed<Order>>>(model);
}
/// dmv and lgvi: the moments of J (moser_veselov::DiagonalInertia).
template <class Scheme>
std::unique_ptr<LaneFallback> make_unprocessed(const system::FreeBody& model, EnsembleModel& constants) {
  constants.preprocessed = false;
  for (int i = 0; i < 3; ++i) constants.moments[i] = model.inertia.J(i, i);
  return std::make_unique<DmvFallback<Scheme>>(model);
}

}  // namespace

std::unique_ptr<LaneFallback> make_dmv_fallback(std::string_view scheme, const system::FreeBody& model,
                                                EnsembleModel& constants) {
  static_assert(12 + moser_veselov::CayleyPredictor::memory_size == static_cast<std::size_t>(dmv_rows::memory),
                "dmv_rows must follow StepMemory::save");
  if (scheme == "dmv") return make_unprocessed<Dmv>(model, constants);
  if (scheme == "lgvi") return make_unprocessed<Lgvi>(model, constants);
  if (scheme == "dmv-pre4") return make_for<4>(model, constants);
  if (scheme == "dmv-pre6") return make_for<6>(model, constants);
  if (scheme == "dmv-pre8") return make_for<8>(model, constants);
  if (scheme == "dmv-pre10") return make_for<10>(model, constants);
  return nullptr;
}

}  // namespace lgi::integrators::ensemble

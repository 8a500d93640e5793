#pragma once
// The trajectories of a sweep: trajectory i's inputs, its scene and its
// initial state, each a function of i and the spec alone, so any thread on
// any rank computes the same trajectory i (experiments/SWEEPS.md).
//
// Index order: the grid axes ([[vary]] without `uniform`) form a Cartesian
// product, the first listed varying slowest; each grid point has `samples`
// trajectories, i = grid_point · samples + sample. Random draws (uniform
// entries, level-set points) come from a counter-based generator keyed by
// (seed, i, entry): SplitMix64 (G. Steele, D. Lea, C. Flood, "Fast splittable
// pseudorandom number generators", OOPSLA 2014), never from a shared stream.
#include <cstdint>
#include <string>
#include <stdexcept>
#include <vector>

#include "experiments/io/sweep_spec.hpp"
#include "integrators/system/rigid_body.hpp"
#include "integrators/system/scene.hpp"

namespace lgi::experiments {

/// Why a trajectory could not be set up (an empty level set for its body);
/// recorded as the trajectory's failure, never thrown out of the sweep.
struct TrajectorySetupError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class SweepPlan {
 public:
  /// Validates every grid value against the scene (InputError naming the
  /// spec's key) and, with [level_set], that the level set is not empty.
  SweepPlan(const SweepSpec& spec, const system::Scene& base);

  std::int64_t count() const { return count_; }
  const std::vector<InputColumn>& input_columns() const { return columns_; }
  /// Numbers per trajectory over all input columns.
  int input_width() const { return width_; }

  /// Trajectory i's inputs, the input columns concatenated (level-set
  /// columns are filled by initial_state()).
  void inputs(std::int64_t i, std::vector<double>& flat) const;
  /// Whether trajectories with these inputs share the scene of `other`
  /// (only initial-state keys differ): then the model can be reused.
  bool same_scene(const std::vector<double>& a, const std::vector<double>& b) const;
  /// The scene with the inputs' body and term keys applied (the base scene
  /// when none varies). InputError if the values make an invalid scene.
  system::Scene scene(const std::vector<double>& flat) const;
  /// The initial state of trajectory i: the scene's, with the inputs'
  /// initial keys applied, or a level-set draw (written into flat).
  /// TrajectorySetupError if the level set is empty for this scene.
  system::State initial_state(std::int64_t i, const system::Scene& scene, std::vector<double>& flat) const;

 private:
  const SweepSpec& spec_;
  const system::Scene& base_;
  std::int64_t count_ = 0;
  std::vector<InputColumn> columns_;
  std::vector<int> offsets_;  // of each vary entry in the flat inputs
  int width_ = 0;
  int level_offset_ = -1;     // of the level-set columns (gamma, then angular momentum)
  bool scene_varies_ = false;
};

}  // namespace lgi::experiments

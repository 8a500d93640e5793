#pragma once
// The observables of one run of an SO(3) scene at uniform times, for frequency
// analysis (experiments/FREQUENCIES.md): the scheme runs through the registry and
// the one time loop (integrators/core/stepper_loop.hpp) with RunConfig::output_times,
// so the samples lie on t0 + k D whatever the scheme's own steps.
#include <atomic>
#include <optional>
#include <utility>
#include <string>
#include <vector>

#include "integrators/registry/registry.hpp"
#include "integrators/system/scene.hpp"

namespace lgi::experiments::frequency {

/// The names, as in the trajectory file (1-based components): angular_momentum_1..3 (Π),
/// gamma_1..3 (Γ = Rᵀe3, the vertical in the body frame), angular_velocity_1..3 (Ω).
const std::vector<std::string>& observable_names();

/// The names of a Cardan top's observables (T³ × ℝ³, docs/cardan.md): cardan_angle_1..3 (q, not
/// wrapped), cardan_momentum_1..3 (p), cos_cardan_angle_1..3 and sin_cardan_angle_1..3 (cos q, sin q:
/// quasi-periodic whether an angle librates or circulates). Sampled by cardan_series.hpp.
const std::vector<std::string>& cardan_observable_names();

/// The real observables that `observables` need, each once, in order of first use: a name, or a
/// complex pair "A+iB" (A + iB, e.g. angular_momentum_1+iangular_momentum_2) of two names, of either
/// list above. Throws std::invalid_argument naming an unknown observable.
std::vector<std::string> components_of(const std::vector<std::string>& observables);

/// The two names of a complex pair "A+iB", or nothing for a real observable.
std::optional<std::pair<std::string, std::string>> complex_pair(const std::string& observable);

struct SamplingSettings {
  double t_end = 0.0;      // the run is [t0, t0 + K D] with K D ≤ t_end − t0 (whole intervals only)
  double dt = 0.0;         // the scheme's step (an adaptive scheme's first trial step)
  double tol = 0.0;        // adaptive schemes only
  double output_dt = 0.0;  // D; a fixed-step scheme needs a whole multiple of dt
};

struct SampledRun {
  double t0 = 0.0, output_dt = 0.0;
  std::vector<std::vector<double>> series;  // one per requested name, K + 1 samples each
  integrators::RunStats stats;
};

/// Throws std::invalid_argument naming the problem (an unknown observable, a D that is not a
/// multiple of a fixed step, fewer than 16 samples, a scheme that cannot run on the scene).
/// A run that fails (stats.ok false) returns what it sampled.
SampledRun sample_observables(const system::Scene& scene, const integrators::SchemeInfo& scheme,
                              const SamplingSettings& settings, const std::vector<std::string>& names,
                              const std::atomic<bool>* stop);

}  // namespace lgi::experiments::frequency

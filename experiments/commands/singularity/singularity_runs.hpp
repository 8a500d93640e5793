#pragma once
// The runs of the Euler-angle singularity study (experiments/SINGULARITY.md):
// which methods, and per run its counts, CPU time, step history, raw Euler
// angles and centre of mass on a common grid against a tight reference.
#include <atomic>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "integrators/baselines/baselines.hpp"
#include "integrators/registry/registry.hpp"

namespace lgi::experiments::singularity {

namespace bl = integrators::baselines;
using lie::Mat3;
using lie::Vec3;
using system::State;

inline constexpr double nan = std::numeric_limits<double>::quiet_NaN();
inline constexpr double reference_tol = 1e-12;
inline constexpr const char* reference_scheme = "rkmk-dp54";
inline constexpr double grid_spacing = 0.01;

struct Method {
  std::string name;   // as in the tables: a registry name, "+ (unguarded)" for the euler runs without guard
  std::string label;  // HDF5 group name
  bool baseline = false;
  bl::BaselineId id{bl::Coordinates::euler_zxz, bl::Stepper::rk4};
  bool guarded = true;
  const integrators::SchemeInfo* scheme = nullptr;  // the registry's entry, baselines included
  bool adaptive = false;
};

/// Which runs a baseline is: euler-zxz with its singularity guard.
inline bool is_euler(const Method& m) { return m.baseline && m.id.coordinates == bl::Coordinates::euler_zxz; }
/// "-" (no guard: not an Euler-angle chart), "on" or "off".
inline const char* guard_text(const Method& m) { return !is_euler(m) ? "-" : m.guarded ? "on" : "off"; }
/// The stepper column: odeint's stepper for a baseline, the scheme's name otherwise.
inline std::string stepper_text(const Method& m) {
  return m.baseline ? std::string(bl::stepper_name(m.id.stepper)) : m.name;
}

struct SceneCase {
  std::string key;   // HDF5 group name
  std::string file;  // path
  double t_end_quick;
};

/// One scene of the study as it is run: its model, span, steps and grid.
struct StudyScene {
  const system::Scene* scene = nullptr;
  system::AnyModel model;
  double t_end = 0.0, tol = 0.0, dt = 0.0;
  Vec3 chi = Vec3::Zero();   // centre of mass, body frame
  Mat3 J_inv = Mat3::Identity();
  std::vector<double> grid;  // times of the common grid
};

struct RunRecord {
  Method method;
  integrators::RunStats stats;  // of the history run
  double cpu_seconds = 0.0;   // of the timing run (no observer work)
  std::vector<double> step_end, step_size;
  std::vector<double> e_time, psi, theta, phi, theta_dot;  // euler-zxz only
  std::vector<double> com;                                  // [G][3], NaN where not reached
  std::vector<double> com_deviation;                        // [G]
  double com_max_deviation = nan;
  std::int64_t com_points = 0;
  double min_abs_sin_theta = nan;
  double h_min = nan, h_median = nan, h_max = nan, t_at_h_min = nan;
};

/// The methods of the study on a model: every baseline (euler-zxz also
/// unguarded) and the Lie-group schemes that apply; a few with --quick.
std::vector<Method> study_methods(bool quick, const system::AnyModel& model);

/// The reference centre of mass on the grid ([G][3], NaN where not reached);
/// nullopt if `stop` (RunConfig::stop: read every step) ended the run.
std::optional<std::vector<double>> reference_center_of_mass(const StudyScene& sc, const std::atomic<bool>* stop);

/// Runs one method three times (timing, history, grid) and compares with `reference`;
/// nullopt if `stop` ended one of the three (the run is then not a result).
std::optional<RunRecord> run_study_method(const Method& m, const StudyScene& sc, const std::vector<double>& reference,
                                          const std::atomic<bool>* stop);

}  // namespace lgi::experiments::singularity

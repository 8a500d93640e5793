#pragma once
// The sweep specification: a TOML file read by `lgi sweep --spec FILE`
// (format and bad-input rules: experiments/SWEEPS.md). It names a base
// scene, a scheme and its step or tolerance, t_end, what varies from one
// trajectory to the next ([[vary]], [level_set]) and the surfaces whose
// crossings are recorded ([[event]]). Plain data; the trajectories are
// generated from it by analysis/sweep_plan.hpp.
//
// Every problem throws InputError with one line
//   <spec>:<line>: [table] key: what is wrong
// as the scene reader does (io/scene_reader.hpp).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace lgi::experiments {

/// A /sweep column of n×width numbers: a varied input, or a level-set draw.
struct InputColumn {
  std::string name;
  int width = 1;
};

/// One varied scene key. A grid entry contributes an axis of the Cartesian
/// product; a random entry is drawn afresh for every trajectory.
struct VaryEntry {
  std::string key;     // as written, e.g. "initial.angular_momentum" or "body.mass"
  std::string table;   // "initial"
  std::string name;    // "angular_momentum"
  int component = 0;   // 1..3 (one component of a vector key), 0: the whole key
  int width = 1;       // numbers per trajectory (1, 3 or 4)
  bool random = false; // uniform draw per trajectory (`uniform`), else a grid axis
  std::vector<std::vector<double>> values;  // grid: the values in order
  std::vector<double> low, high;            // random: the box
  std::string column;  // the /sweep column of the varied input
  std::uint32_t line = 0;
  /// Whether the key sets the initial state only (applied without re-reading the scene).
  bool initial_state() const { return table == "initial"; }
};

/// A surface g = 0 whose crossings are recorded (integrators/core/events.hpp).
struct EventSpec {
  /// gamma_rate: d(Γ·e)/dt = (Γ × Ω)·e for the body axis e = `axis`, Richter's
  /// Poincaré section (docs/atlas.md §6); from a spec, e is the body axis `component`.
  enum class Quantity { angular_momentum, angular_velocity, gamma, gamma_rate };
  std::string name;     // e.g. "gamma3_rising"
  Quantity quantity = Quantity::gamma;
  int component = 1;    // 1..3
  double value = 0.0;   // g = quantity[component] − value
  int direction = 0;    // +1 rising, −1 falling, 0 both
  std::array<double, 3> axis{};  // gamma_rate: the unit body axis e (a spec sets e_component)
};

/// The density of a level-set draw (docs/atlas.md §6): the Liouville measure
/// of {H = h, Π·Γ = l} (the default), or Γ uniform on the sphere (the draw
/// of lgi before the measure was chosen; kept to reproduce those runs).
enum class LevelMeasure { liouville, uniform };

/// "liouville" or "uniform".
const char* level_measure_name(LevelMeasure m);
/// The measure named `name`, or nothing if it is neither name.
std::optional<LevelMeasure> level_measure_from_name(const std::string& name);

/// Initial conditions drawn on {H = h, Π·Γ = l} (SWEEPS.md says how).
struct LevelSetSpec {
  double h = 0.0;
  double l = 0.0;
  std::uint32_t line = 0;
  LevelMeasure measure = LevelMeasure::liouville;
  /// lgi poincare --seeds: trajectory i starts at (Γ, Π) = seeds[i] instead of a draw
  /// (set by the command, never read from a spec file).
  std::vector<std::array<double, 6>> seeds;
};

struct SweepSpec {
  std::string file;        // as given
  std::string text;        // the whole file, for provenance and --resume
  std::string scene_path;  // resolved against the spec's directory
  std::string scheme;
  std::optional<double> dt, tol, t_end;
  std::uint64_t seed = 0;
  std::int64_t samples = 1;       // random draws per grid point
  std::int64_t chunk = 0;         // trajectories per chunk (0: automatic)
  std::int64_t max_events = 10000;  // per trajectory
  std::int64_t monitor_every = 1;   // invariant errors every N steps (and at the end)
  std::int64_t trajectory_every = 0;  // a thinned trajectory: the state every N steps and at the end (0: none)
  std::vector<VaryEntry> vary;
  std::optional<LevelSetSpec> level_set;
  std::vector<EventSpec> events;

  /// Grid points: the product of the grid axes' lengths (1 without axes).
  std::int64_t grid_points() const;
  /// Trajectories: grid_points() × samples.
  std::int64_t count() const { return grid_points() * samples; }
};

/// Reads and validates the spec at `path` (InputError on any problem).
SweepSpec read_sweep_spec(const std::string& path);
/// The same from its text; `path` names the file in messages and anchors the scene path.
SweepSpec parse_sweep_spec(const std::string& text, const std::string& path);

}  // namespace lgi::experiments

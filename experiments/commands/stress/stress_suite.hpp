#pragma once
// The stress suite's cases (experiments/STRESS.md): each variant is a scene
// built in memory from a shipped scene (or inline), a step or tolerance, a
// reference to compute and a written criterion for a pass.
#include <limits>
#include <string>
#include <vector>

#include "experiments/io/number_format.hpp"
#include "integrators/system/rigid_body.hpp"
#include "integrators/system/scene.hpp"

namespace lgi::experiments::stress {

using lie::Mat3;
using lie::Vec3;
using system::Scene;
using system::State;

inline constexpr double nan = std::numeric_limits<double>::quiet_NaN();
inline constexpr double inf = std::numeric_limits<double>::infinity();

/// Numbers in the suite's descriptions, reasons and summary: 17 significant digits unless asked.
inline std::string fmt(double x, int precision = 17) { return format_general(x, precision); }

inline std::string short_number(double x) { return fmt(x, 3); }

/// What counts as a pass for one scheme on one variant (STRESS.md).
struct Criterion {
  double max_error = 1e-3;         // an ok run needs a finite error <= this
  bool failure_passes = false;     // a failed run (stopped with a reason) counts as pass
  bool fixed_one_step = false;     // fixed-step schemes must take exactly one step (dt > t_end)
  bool zero_time = false;          // t_end = 0: no step, the initial state returned (to round-off)
  bool units = false;              // rescaled run agrees with the SI run to max_error (relative)
  bool invariants_only = false;    // the final state is ill-conditioned: judge the invariant errors instead
  std::string text;                // the criterion in words, for /cases
};

struct UnitScale {
  double length = 1.0, mass = 1.0, time = 1.0;  // value in the new unit = factor × value in SI
};

struct Reference {
  std::string kind;    // "exact", "converged", "initial state", "same scheme in SI units"
  std::string scheme;  // for converged: the scheme and tolerance used
  double tol = nan;
  double estimated_error = nan;  // see STRESS.md ("References")
  std::string check;             // how the estimate was obtained
  bool available = false;
  State state;
  double momentum_scale = 1.0;  // the largest |Π| along the reference trajectory (momentum errors divide by it)
  std::string failure;          // why no reference could be computed
};

struct Variant {
  std::string case_id, variant;
  std::string scene_label;  // the shipped scene it starts from, or "inline"
  std::string description;  // what was changed
  Scene scene;
  double t_end = 0.0;
  double dt = 0.0;          // fixed step
  double tol = 1e-8;        // adaptive schemes
  double first_step = 0.0;  // adaptive schemes' first trial step (0: their own choice)
  Criterion criterion;
  Reference reference;
  // units
  bool units = false;
  UnitScale scale;
  Scene scaled;
};

struct SuiteSettings {
  bool quick = false;
  std::string scenes_dir;  // the shipped scenes (scenes_location.hpp)
};

/// Builds every variant of the suite (STRESS.md lists them with their criteria).
std::vector<Variant> build_suite(const SuiteSettings& settings);

}  // namespace lgi::experiments::stress

// lgi stress: the suite of stiff and extreme cases (experiments/STRESS.md),
// each run against every registered scheme (or those of --schemes), with an
// outcome, an error against a reference, the largest invariant error, the
// work, and a pass flag computed from the case's written criterion.
//
// Data flow per row: a scene built in memory (a shipped scene read with
// read_scene() and modified) → make_model → the scheme's registry RunFunction
// with an observer that tracks the invariant errors and the CPU budget →
// outcome and error → pass. Rows go through ResultsFile (results_file.hpp)
// to /results of <out>.partial and <out>.csv.partial as they are made (a
// killed run leaves them readable); both are renamed on success
// (RESULTS.md, "stress"). Each variant's set-up, reference and criterion go
// to the attributes of a group /case_NN.
#include <unistd.h>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "experiments/scenes_location.hpp"
#include "experiments/scheme_lookup.hpp"
#include "experiments/commands.hpp"
#include "experiments/exit_status.hpp"
#include "experiments/h5md_writer.hpp"
#include "experiments/results_file.hpp"
#include "experiments/scene_reader.hpp"
#include "experiments/trajectory_observer.hpp"
#include "integrators/registry.hpp"
#include "integrators/system/free_body_exact.hpp"
#include "integrators/system/invariants.hpp"
#include "lgi/build_info.hpp"
#include "lie/charts.hpp"

namespace lgi::experiments {
namespace {

using integrators::SchemeInfo;
using lie::Mat3;
using lie::Vec3;
using system::Scene;
using system::State;

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double pi = std::numbers::pi;

// ---- options -------------------------------------------------------------------

struct StressOptions {
  std::string schemes;  // comma-separated; empty: every registered scheme
  bool quick = false;
  std::string out;
  bool force = false;
  bool quiet = false;
  std::optional<double> budget;  // CPU seconds per run
  std::string scenes_dir;        // --scenes-dir; empty: found beside the executable
  std::string command_line;
};

extern "C" void stress_request_interrupt(int) { interrupt_requested.store(true); }

std::string fmt(double x, int precision = 17) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  std::ostringstream s;
  s.precision(precision);
  s << x;
  return s.str();
}

std::string short_number(double x) { return fmt(x, 3); }

double cpu_now() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

// ---- the cases -------------------------------------------------------------------

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

Scene shipped(const std::string& dir, const std::string& file) { return read_scene(dir + "/" + file); }

Mat3 generic_attitude() { return lie::exp_so3(Vec3(0.3, -0.2, 0.5)); }

/// A free body with principal moments `moments`, attitude R0 and body Ω0.
Scene free_body(const std::string& name, const Vec3& moments, const Vec3& omega0, bool allow_unphysical = false) {
  Scene s;
  s.name = name;
  s.file = "(in memory: " + name + ")";
  s.inertia = moments.asDiagonal();
  s.allow_unphysical = allow_unphysical;
  s.initial.R = generic_attitude();
  s.initial.Pi = s.inertia * omega0;
  return s;
}

/// |Ω0| of a scene's initial state.
double omega0_norm(const Scene& s) { return (s.inertia.inverse() * s.initial.Pi).norm(); }

/// Π0 of the book with 2H|Π|⁻² = (1 + δ)/J2 (δ = 0: on the separatrix), given Π2, Π3;
/// Π1 > 0 solved in long double. Needs J1 > J2 > J3 (diagonal).
Vec3 separatrix_momentum(const Mat3& J, double pi2, double pi3, long double delta) {
  const long double j1 = J(0, 0), j2 = J(1, 1), j3 = J(2, 2);
  const long double c = (1.0L + delta) / j2;
  const long double p2 = pi2, p3 = pi3;
  // Π·J⁻¹Π − c|Π|² = 0:  Π1² (1/J1 − c) + Π2² (1/J2 − c) + Π3² (1/J3 − c) = 0
  const long double p1sq = -(p2 * p2 * (1.0L / j2 - c) + p3 * p3 * (1.0L / j3 - c)) / (1.0L / j1 - c);
  return Vec3(static_cast<double>(std::sqrt(p1sq)), pi2, pi3);
}

/// 2H J2 |Π|⁻² − 1 in long double: the achieved offset from the separatrix.
long double separatrix_offset(const Mat3& J, const Vec3& p) {
  long double twoH = 0.0L, n2 = 0.0L;
  for (int i = 0; i < 3; ++i) {
    const long double x = p(i);
    twoH += x * x / static_cast<long double>(J(i, i));
    n2 += x * x;
  }
  return twoH * static_cast<long double>(J(1, 1)) / n2 - 1.0L;
}

Scene rescaled(const Scene& si, const UnitScale& u) {
  Scene s = si;
  const double sJ = u.mass * u.length * u.length;  // kg m²
  const double sT = u.time;
  s.inertia = si.inertia * sJ;
  if (s.mass) *s.mass = *si.mass * u.mass;
  if (s.center_of_mass) *s.center_of_mass = *si.center_of_mass * u.length;
  if (s.gravity) s.gravity->g = si.gravity->g * u.length / (sT * sT);
  if (s.spring) {
    s.spring->stiffness = si.spring->stiffness * sJ / (sT * sT);  // N m/rad = kg m² s⁻²
    s.spring->damping = si.spring->damping * sJ / sT;             // N m s/rad = kg m² s⁻¹
  }
  if (s.drive) {
    s.drive->torque_amplitude = si.drive->torque_amplitude * (sJ / (sT * sT));
    s.drive->angular_frequency = si.drive->angular_frequency / sT;
  }
  s.initial.Pi = si.initial.Pi * (sJ / sT);  // kg m² s⁻¹
  if (si.t_end) s.t_end = *si.t_end * sT;
  if (s.dt) *s.dt = *si.dt * sT;
  s.file = si.file + " (rescaled)";
  return s;
}

struct SuiteSettings {
  bool quick = false;
  std::string scenes_dir;  // the shipped scenes (scenes_location.hpp)
};

/// Builds every variant of the suite (STRESS.md lists them with their criteria).
std::vector<Variant> build_suite(const SuiteSettings& set) {
  const bool quick = set.quick;
  std::vector<Variant> out;
  const Scene book = shipped(set.scenes_dir, "dzhanibekov_book_axis2.toml");
  const Scene top = shipped(set.scenes_dir, "heavy_top_trindade_1.toml");
  const Scene spring = shipped(set.scenes_dir, "stiff_damped_spring.toml");

  auto add = [&](Variant v) { out.push_back(std::move(v)); };

  // 1. Large steps: h|Ω0| from 0.1 to past π.
  {
    struct Step {
      double value;
      std::string label;
    };
    std::vector<Step> steps = {{0.1, "0.1"}, {0.5, "0.5"}, {1.0, "1"}, {2.0, "2"}, {3.0, "3"}, {pi, "pi"}, {4.0, "4"}};
    if (quick) steps = {{0.5, "0.5"}, {pi, "pi"}, {4.0, "4"}};
    struct Base {
      const Scene* scene;
      std::string label, file;
      double t_end;
    };
    const std::vector<Base> bases = {{&book, "book", "dzhanibekov_book_axis2.toml", quick ? 2.0 : 4.0},
                                     {&top, "top", "heavy_top_trindade_1.toml", quick ? 0.5 : 2.0}};
    for (const auto& b : bases) {
      const double w = omega0_norm(*b.scene);
      for (const auto& st : steps) {
        Variant v;
        v.case_id = "large-steps";
        v.variant = b.label + " h|Omega|=" + st.label;
        v.scene_label = b.file;
        v.description = "shipped scene, t_end = " + fmt(b.t_end) + ", h = " + st.label + "/|Omega0| (|Omega0| = " +
                        fmt(w, 6) + " rad/s); adaptive schemes: tol 1e-8, first trial step h";
        v.scene = *b.scene;
        v.t_end = b.t_end;
        v.dt = st.value / w;
        v.tol = 1e-8;
        v.first_step = v.dt;
        v.criterion.max_error = 1e-2;
        v.criterion.failure_passes = st.value >= 1.0;
        add(std::move(v));
      }
    }
  }

  // 2. The separatrix of the book (and of a body whose separatrix is exactly representable).
  //    Up to t = 4 the book's flip and the approach to the opposite saddle are well conditioned;
  //    exactly on the separatrix the exact orbit then creeps towards the saddle for ever, while
  //    any perturbation (the rounding of Π0 included) grows like e^(λt), λ ≈ 4.6 s⁻¹, and flips
  //    back: by t = 10 no double-precision method can follow it, and only the invariants are judged.
  {
    const Mat3 J = book.inertia;
    const double pi2 = 10.0 * J(1, 1), pi3 = 0.01 * J(2, 2);
    struct Off {
      long double delta;
      std::string label;
      double t_end;
      bool invariants_only;
    };
    std::vector<Off> offsets = {{0.0L, "offset=0", 4.0, false},
                                {0.0L, "offset=0 t_end=10", 10.0, true},
                                {1e-12L, "offset=+1e-12", 10.0, false},
                                {-1e-12L, "offset=-1e-12", 10.0, false}};
    if (quick) offsets = {{0.0L, "offset=0", 3.0, false}, {1e-12L, "offset=+1e-12", 3.0, false}};
    for (const auto& o : offsets) {
      Variant v;
      v.case_id = "separatrix";
      v.variant = "book " + o.label;
      v.scene_label = "dzhanibekov_book_axis2.toml";
      v.scene = book;
      v.scene.initial.R = generic_attitude();
      v.scene.initial.Pi = separatrix_momentum(J, pi2, pi3, o.delta);
      const long double achieved = separatrix_offset(J, v.scene.initial.Pi);
      v.description = "book inertia, R0 = exp((0.3,-0.2,0.5)^), Pi0 = (" + fmt(v.scene.initial.Pi.x()) + ", " +
                      fmt(pi2) + ", " + fmt(pi3) + ") with 2H|Pi|^-2 = (1 + delta)/J2, delta = " +
                      fmt(static_cast<double>(o.delta)) + " (achieved, long double: " +
                      fmt(static_cast<double>(achieved), 3) + "), t_end = " + fmt(o.t_end);
      v.t_end = o.t_end;
      v.dt = 1e-3;
      v.tol = 1e-10;
      v.criterion.invariants_only = o.invariants_only;
      add(std::move(v));
    }
    // J = (3, 1.5, 1): 2/J2 = 1/J1 + 1/J3, so Π1 = Π3 lies exactly on the separatrix; with
    // Π1 = Π3 = 2^-7 every term of the exact flow's Δ is exact and it takes its separatrix branch.
    std::vector<std::pair<double, bool>> ends = {{quick ? 3.0 : 4.0, false}};
    if (!quick) ends.push_back({10.0, true});
    for (const auto& [t_end, invariants_only] : ends) {
      Variant v;
      v.case_id = "separatrix";
      v.variant = std::string("dyadic body offset=0 (exact)") + (invariants_only ? " t_end=10" : "");
      v.scene_label = "inline";
      v.scene = free_body("dyadic separatrix body", Vec3(3.0, 1.5, 1.0), Vec3::Zero(), /*allow_unphysical=*/true);
      v.scene.initial.Pi = Vec3(0.0078125, 15.0, 0.0078125);
      v.description =
          "J = (3, 1.5, 1) (allow_unphysical), R0 = exp((0.3,-0.2,0.5)^), Pi0 = (2^-7, 15, 2^-7): exactly on the "
          "separatrix in binary arithmetic (2/J2 = 1/J1 + 1/J3, Pi1 = Pi3), t_end = " + fmt(t_end);
      v.t_end = t_end;
      v.dt = 1e-3;
      v.tol = 1e-10;
      v.criterion.invariants_only = invariants_only;
      add(std::move(v));
    }
  }

  // 3. Exact passage through theta = pi: a heavy top swinging with no spin through the bottom.
  {
    struct Swing {
      double theta0, thetadot0, spin;
      std::string label, what;
    };
    std::vector<Swing> swings = {
        {pi / 3, 0.0, 0.0, "release theta0=pi/3", "released at rest from theta0 = pi/3, psi = phi = 0: a planar "
                                                   "swing through theta = pi and on to 5 pi/3, and back"},
        {pi, 2.0, 0.0, "start theta0=pi thetadot0=2", "starts at the bottom (theta0 = pi exactly in the chart) with "
                                                      "thetadot0 = 2 rad/s, no spin"}};
    if (!quick)
      swings.push_back({pi / 3, 0.0, 0.01, "release theta0=pi/3 spin=0.01",
                        "released from theta0 = pi/3 with phidot0 = 0.01: passes next to theta = pi, not through"});
    for (const auto& sw : swings) {
      Variant v;
      v.case_id = "theta-pi";
      v.variant = sw.label;
      v.scene_label = "heavy_top_trindade_1.toml";
      v.scene = top;
      v.scene.initial.R = lie::rot_x(sw.theta0);
      v.scene.initial.Pi = top.inertia * Vec3(sw.thetadot0, 0.0, sw.spin);
      v.description = "Trindade-Sampaio top (m = 5, J = diag(5.8, 5.8, 1), chi = (0,0,1), g = 9.81), " + sw.what;
      v.t_end = quick ? 1.5 : 5.0;
      v.dt = 2e-3;  // h |Omega|max <= 0.01
      v.tol = 1e-8;
      add(std::move(v));
    }
  }

  // 4. A fast top: spin 1000 rad/s.
  {
    std::vector<double> hw = {0.01};
    if (!quick) hw.push_back(0.1);
    for (double c : hw) {
      Variant v;
      v.case_id = "fast-top";
      v.variant = "spin=1000 h|Omega|=" + short_number(c);
      v.scene_label = "heavy_top_trindade_1.toml";
      v.scene = top;
      v.scene.initial.Pi = top.inertia * Vec3(0.0, 0.0, 1000.0);
      v.t_end = quick ? 0.02 : 1.0;
      v.dt = c / omega0_norm(v.scene);
      v.tol = 1e-8;
      v.description = "Trindade-Sampaio top 1 with phidot0 = 1000 rad/s (theta0 = pi/9), t_end = " + fmt(v.t_end) +
                      ", h = " + fmt(v.dt);
      add(std::move(v));
    }
  }

  // 5. Extreme inertia (free bodies, exact reference), at h|Omega0| = 0.01 over 20 rad of rotation
  //    (|Omega0| t_end = 20), the resolution at which the ordinary book is resolved to about 1e-4
  //    by second-order schemes: what is measured is the effect of the inertia, not of the step.
  {
    struct Body {
      std::string case_id, label;
      Vec3 moments, omega0;
    };
    std::vector<Body> bodies = {
        {"needle", "J=(1,1,1e-4) Omega0=(1,0.5,2)", Vec3(1.0, 1.0, 1e-4), Vec3(1.0, 0.5, 2.0)},
        {"flat-plate", "J=(1,1,2) Omega0=(1,0.5,2)", Vec3(1.0, 1.0, 2.0), Vec3(1.0, 0.5, 2.0)},
        {"near-sphere", "J=(1,1+1e-9,1+2e-9) Omega0=(1,0.5,2)", Vec3(1.0, 1.0 + 1e-9, 1.0 + 2e-9),
         Vec3(1.0, 0.5, 2.0)}};
    if (!quick) {
      bodies.push_back({"needle", "J=(1,1,1e-4) Omega0=(1,0.5,100)", Vec3(1.0, 1.0, 1e-4), Vec3(1.0, 0.5, 100.0)});
      bodies.push_back({"flat-plate", "J=(1,2,3) Omega0=(1,0.5,2)", Vec3(1.0, 2.0, 3.0), Vec3(1.0, 0.5, 2.0)});
      bodies.push_back({"near-sphere", "J=(1,1+1e-9,1+2e-9) Omega0=(1,1e-3,2)", Vec3(1.0, 1.0 + 1e-9, 1.0 + 2e-9),
                        Vec3(1.0, 1e-3, 2.0)});
    }
    for (const auto& b : bodies) {
      Variant v;
      v.case_id = b.case_id;
      v.variant = b.label;
      v.scene_label = "inline";
      v.scene = free_body(b.case_id, b.moments, b.omega0);
      const double w = omega0_norm(v.scene);
      v.t_end = 20.0 / w;
      v.dt = 0.01 / w;
      v.tol = 1e-8;
      v.description = "free body J = diag(" + fmt(b.moments.x()) + ", " + fmt(b.moments.y()) + ", " +
                      fmt(b.moments.z()) + "), R0 = exp((0.3,-0.2,0.5)^), Omega0 = (" + fmt(b.omega0.x()) + ", " +
                      fmt(b.omega0.y()) + ", " + fmt(b.omega0.z()) + "), h|Omega0| = 0.01, t_end = 20/|Omega0| = " +
                      fmt(v.t_end, 6);
      add(std::move(v));
    }
  }

  // 6. Stiffness: the stiff damped spring at h c/J1 from 1 to 1000.
  {
    std::vector<double> ratios = {1.0, 2.0, 3.0, 10.0, 100.0, 1000.0};
    if (quick) ratios = {1.0, 10.0, 1000.0};
    const double c_over_j = spring.spring->damping / spring.inertia(0, 0);  // the fastest mode, 1000 s^-1
    for (double r : ratios) {
      Variant v;
      v.case_id = "stiffness";
      v.variant = "h*c/J=" + short_number(r);
      v.scene_label = "stiff_damped_spring.toml";
      v.scene = spring;
      v.t_end = quick ? 2.0 : 10.0;
      v.dt = r / c_over_j;
      v.tol = 1e-8;
      v.first_step = v.dt;
      v.description = "shipped scene (k = 100, c = 1000, J = (1,2,3)), h = " + fmt(v.dt) + " (h c/J1 = " +
                      short_number(r) + "), t_end = " + fmt(v.t_end) +
                      "; adaptive schemes: tol 1e-8, first trial step h";
      // Beyond the explicit schemes' stability limit (RK4: h c/J < 2.79) a loud failure is allowed.
      v.criterion.failure_passes = r > 2.0;
      add(std::move(v));
    }
  }

  // 7. Units: the same scene in mm and mg (and ms).
  {
    struct Unit {
      UnitScale scale;
      std::string label;
    };
    std::vector<Unit> units = {{{1e3, 1e6, 1.0}, "mm mg s"}, {{1e3, 1e6, 1e3}, "mm mg ms"}};
    struct Base {
      const Scene* scene;
      std::string label, file;
    };
    std::vector<Base> bases = {{&book, "book", "dzhanibekov_book_axis2.toml"},
                               {&top, "top", "heavy_top_trindade_1.toml"},
                               {&spring, "spring", "stiff_damped_spring.toml"}};
    if (quick) {
      units = {{{1e3, 1e6, 1e3}, "mm mg ms"}};
      bases = {{&book, "book", "dzhanibekov_book_axis2.toml"}, {&top, "top", "heavy_top_trindade_1.toml"}};
    }
    for (const auto& b : bases) {
      for (const auto& u : units) {
        Variant v;
        v.case_id = "units";
        v.variant = b.label + " " + u.label;
        v.scene_label = b.file;
        v.scene = *b.scene;
        v.t_end = quick ? 0.5 : 2.0;
        v.dt = *b.scene->dt;
        v.tol = 1e-8;
        v.units = true;
        v.scale = u.scale;
        v.scaled = rescaled(*b.scene, u.scale);
        v.description = "shipped scene, t_end = " + fmt(v.t_end) + ", dt = " + fmt(v.dt) +
                        ", run in SI and with lengths x" + fmt(u.scale.length) + ", masses x" + fmt(u.scale.mass) +
                        ", times x" + fmt(u.scale.time) +
                        " (J, Pi, k, c x M L^2 T^-k; g x L T^-2; chi x L; t, dt x T)";
        v.criterion.units = true;
        v.criterion.max_error = 1e-10;
        add(std::move(v));
      }
    }
  }

  // 8. Degenerate runs: t_end = 0, and dt > t_end.
  {
    struct Base {
      const Scene* scene;
      std::string label, file;
    };
    const std::vector<Base> bases = {{&book, "book", "dzhanibekov_book_axis2.toml"},
                                     {&top, "top", "heavy_top_trindade_1.toml"},
                                     {&spring, "spring", "stiff_damped_spring.toml"}};
    for (const auto& b : bases) {
      {
        Variant v;
        v.case_id = "degenerate";
        v.variant = b.label + " t_end=0";
        v.scene_label = b.file;
        v.scene = *b.scene;
        v.t_end = 0.0;
        v.dt = *b.scene->dt;
        v.tol = 1e-8;
        v.description = "shipped scene with t_end = 0";
        v.criterion.zero_time = true;
        v.criterion.max_error = 1e-15;
        add(std::move(v));
      }
      {
        Variant v;
        v.case_id = "degenerate";
        v.variant = b.label + " dt=1>t_end=1e-5";
        v.scene_label = b.file;
        v.scene = *b.scene;
        v.t_end = 1e-5;
        v.dt = 1.0;
        v.tol = 1e-8;
        v.first_step = 1.0;
        v.description = "shipped scene with t_end = 1e-5 and dt = 1 (adaptive: first trial step 1)";
        v.criterion.fixed_one_step = true;
        add(std::move(v));
      }
    }
  }
  return out;
}

// ---- running one scheme --------------------------------------------------------------

struct BudgetExceeded : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Tracks the largest invariant error over a run (docs/conventions.md §7: relative to
/// the initial value, absolute where it is 0; the orthogonality error |RᵀR − I|
/// as it is), keeps the latest state, and stops a run past its CPU budget or
/// on SIGINT/SIGTERM.
class StressObserver final : public integrators::Observer {
 public:
  StressObserver(const system::SceneInvariants& invariants, double budget_seconds)
      : inv_(invariants), cpu0_(cpu_now()), budget_(budget_seconds) {}

  void observe(std::int64_t step, double t, const State& s) override {
    const system::InvariantValues v = inv_.evaluate(s);
    if (!have_initial_) {
      initial_ = v;
      have_initial_ = true;
    }
    if (inv_.energy_conserved()) note("energy", system::relative_error(v.energy, initial_.energy));
    const auto& names = inv_.scalar_names();
    for (std::size_t k = 0; k < names.size(); ++k)
      note(names[k].c_str(), system::relative_error(v.scalars[k], initial_.scalars[k]));
    if (inv_.free_body()) {
      const double m0 = initial_.space_momentum.norm();
      const double d = (v.space_momentum - initial_.space_momentum).norm();
      note("angular_momentum_space", m0 > 0.0 ? d / m0 : d);
    }
    note("orthogonality_error", v.orthogonality_error);
    max_momentum_ = std::max(max_momentum_, s.Pi.norm());
    last_ = s;
    last_t_ = t;
    last_step_ = step;
    have_last_ = true;
    if ((++samples_ & 63u) == 0) check();
  }

  double max_error() const { return max_; }
  double max_momentum() const { return max_momentum_; }
  std::string max_name() const { return max_name_ ? max_name_ : ""; }
  bool has_state() const { return have_last_; }
  const State& last_state() const { return last_; }
  double last_time() const { return last_t_; }
  std::int64_t last_step() const { return last_step_; }

 private:
  // `name` points at a string literal or into SceneInvariants::scalar_names(): no allocation per step.
  void note(const char* name, double e) {
    if (std::isnan(max_)) return;  // a NaN stays
    if (std::isnan(e) || e > max_) {
      max_ = e;
      max_name_ = name;
    }
  }
  void check() const {
    if (interrupt_requested.load(std::memory_order_relaxed)) throw Interrupted("interrupted by signal");
    const double used = cpu_now() - cpu0_;
    if (used > budget_)
      throw BudgetExceeded("stopped after " + fmt(used, 3) + " s CPU (the suite's per-run budget, --budget " +
                           fmt(budget_, 3) + " s) at step " + std::to_string(last_step_) + ", t = " + fmt(last_t_, 6));
  }

  const system::SceneInvariants& inv_;
  double cpu0_, budget_;
  bool have_initial_ = false, have_last_ = false;
  system::InvariantValues initial_{};
  double max_ = 0.0;
  const char* max_name_ = nullptr;
  double max_momentum_ = 0.0;
  State last_{};
  double last_t_ = 0.0;
  std::int64_t last_step_ = 0;
  std::uint64_t samples_ = 0;
};

enum class Outcome { ok, refused, failed };

const char* outcome_name(Outcome o) {
  switch (o) {
    case Outcome::ok: return "ok";
    case Outcome::refused: return "refused";
    case Outcome::failed: return "failed";
  }
  return "?";
}

struct RunResult {
  Outcome outcome = Outcome::ok;
  std::string reason;
  bool have_state = false;
  State state;
  double t_final = 0.0;
  double max_invariant_error = nan;
  std::string max_invariant;
  double max_momentum = 0.0;  // the largest |Π| observed
  double cpu_seconds = 0.0;
  std::int64_t steps = 0, rejected_steps = 0, rhs_evaluations = 0;
};

/// Refused or failed, from the reason a run stopped (STRESS.md, "Outcomes").
/// A step refused by design says so in its status (StepStatus::reason):
/// "step refused: ..." (a Cayley step that would turn by pi or more, a
/// modified inertia that is not positive).
Outcome classify_stop(const std::string& status) {
  if (status.rfind("Euler-angle singularity", 0) == 0) return Outcome::refused;  // a chart that will not go on
  if (status.rfind("step refused", 0) == 0) return Outcome::refused;
  if (status.find("needs a free body") != std::string::npos || status.find("needs torques") != std::string::npos)
    return Outcome::refused;
  return Outcome::failed;  // blow-up, a solve that did not converge, step-size collapse, anything else
}

RunResult run_scheme(const SchemeInfo& scheme, const Scene& scene, double t_end, double dt, double tol,
                     double first_step, double budget) {
  RunResult r;
  const system::AnyModel model = system::make_model(scene);
  if (std::string why = integrators::unsupported_reason(scheme, model); !why.empty()) {
    r.outcome = Outcome::refused;
    r.reason = why;
    return r;
  }
  const system::SceneInvariants invariants(scene, model);
  integrators::RunConfig cfg;
  cfg.t0 = 0.0;
  cfg.t_end = t_end;
  cfg.save_every = 1;
  if (scheme.properties.adaptive) {
    cfg.tol = tol;
    cfg.dt = first_step;
  } else {
    cfg.dt = dt;
  }
  StressObserver observer(invariants, budget);
  State state = scene.initial;
  const double cpu0 = cpu_now();
  integrators::RunStats stats;
  bool have_stats = false;
  try {
    stats = scheme.run(model, state, cfg, observer);
    have_stats = true;
  } catch (const Interrupted&) {
    throw;
  } catch (const BudgetExceeded& e) {
    r.outcome = Outcome::failed;
    r.reason = e.what();
  } catch (const std::exception& e) {
    r.outcome = Outcome::failed;
    r.reason = std::string("exception: ") + e.what();
  }
  r.cpu_seconds = have_stats ? stats.cpu_seconds : cpu_now() - cpu0;
  r.max_invariant_error = observer.max_error();
  r.max_invariant = observer.max_name();
  r.max_momentum = observer.max_momentum();
  if (observer.has_state()) {
    r.have_state = true;
    r.state = observer.last_state();
    r.t_final = observer.last_time();
  }
  r.steps = have_stats ? stats.steps : observer.last_step();
  if (have_stats) {
    r.rejected_steps = stats.work.rejected_steps;
    r.rhs_evaluations = stats.work.rhs_evaluations;
    if (!stats.ok) {
      r.outcome = classify_stop(stats.status);
      r.reason = stats.status;
    }
  }
  r.reason = one_line(r.reason);
  return r;
}

// ---- errors -----------------------------------------------------------------------------

/// The rotation nearest to R (polar factor), so that baselines whose matrix
/// or quaternion has drifted off SO(3) get an attitude error that means
/// something; the drift itself is in the invariant errors.
Mat3 nearest_rotation(const Mat3& R) {
  Eigen::JacobiSVD<Mat3> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 U = svd.matrixU();
  const Mat3 V = svd.matrixV();
  if ((U * V.transpose()).determinant() < 0.0) U.col(2) *= -1.0;
  return U * V.transpose();
}

struct StateError {
  double attitude = nan, momentum = nan, total = nan;
};

/// The geodesic angle (docs/conventions.md §7) and |Π/unit − Π_ref| / scale, where scale is the
/// largest |Π| along the reference trajectory (STRESS.md: docs/conventions.md's |Π_ref(t_end)| is
/// ill-conditioned where the reference passes near Π = 0, e.g. a pendulum's turning point).
StateError state_error(const State& s, const State& ref, double scale, double unit = 1.0) {
  StateError e;
  if (!s.R.allFinite() || !s.Pi.allFinite()) {
    e.attitude = e.momentum = e.total = inf;
    return e;
  }
  e.attitude = s.R == ref.R ? 0.0 : lie::geodesic_distance(ref.R, nearest_rotation(s.R));
  const Vec3 p = s.Pi / unit;
  e.momentum = scale > 0.0 ? (p - ref.Pi).norm() / scale : (p - ref.Pi).norm();
  e.total = std::max(e.attitude, e.momentum);
  if (std::isnan(e.total)) e.total = inf;
  return e;
}

// ---- references -------------------------------------------------------------------------

void compute_reference(Variant& v, double budget) {
  Reference& ref = v.reference;
  if (v.units) {
    ref.kind = "same scheme in SI units";
    ref.check = "the row's error is the relative disagreement between the rescaled run (mapped back to SI) and the "
                "SI run";
    return;
  }
  if (v.t_end == 0.0) {
    ref.kind = "initial state";
    ref.available = true;
    ref.state = v.scene.initial;
    ref.momentum_scale = v.scene.initial.Pi.norm();
    ref.estimated_error = 0.0;
    ref.check = "exact";
    return;
  }
  const SchemeInfo* dp54 = integrators::find_scheme("rkmk-dp54");
  auto converged = [&](double tol, std::string& why) -> std::optional<RunResult> {
    if (!dp54) {
      why = "rkmk-dp54 is not registered";
      return std::nullopt;
    }
    const RunResult r = run_scheme(*dp54, v.scene, v.t_end, 0.0, tol, 0.0, 20.0 * budget);
    if (r.outcome != Outcome::ok || !r.have_state) {
      why = "rkmk-dp54 at tol " + fmt(tol, 3) + ": " + r.reason;
      return std::nullopt;
    }
    return r;
  };
  if (v.scene.is_free_body()) {
    ref.kind = "exact";
    ref.scheme = "FreeBodyExactFlow";
    const system::FreeBodyExactFlow flow(system::make_inertia(v.scene.inertia), v.scene.initial);
    ref.state = flow.at(v.t_end);
    ref.momentum_scale = v.scene.initial.Pi.norm();  // |Π| is an invariant
    ref.available = ref.state.R.allFinite() && ref.state.Pi.allFinite();
    if (!ref.available) ref.failure = "the exact flow returned a non-finite state";
    std::string why;
    if (const auto check = converged(1e-12, why)) {
      ref.estimated_error = state_error(check->state, ref.state, ref.momentum_scale).total;
      ref.check = "disagreement with rkmk-dp54 at tol 1e-12 (an upper bound on the exact flow's error, "
                  "dominated by rkmk-dp54's)";
    } else {
      ref.check = "no cross-check: " + why;
    }
    return;
  }
  ref.kind = "converged";
  ref.scheme = "rkmk-dp54";
  ref.tol = 1e-12;
  std::string why;
  const auto fine = converged(1e-12, why);
  if (!fine) {
    ref.failure = why;
    return;
  }
  ref.state = fine->state;
  ref.momentum_scale = fine->max_momentum;
  ref.available = true;
  std::string why2;
  if (const auto coarse = converged(1e-11, why2)) {
    ref.estimated_error = state_error(coarse->state, ref.state, ref.momentum_scale).total;
    ref.check = "disagreement with rkmk-dp54 at tol 1e-11 (an overestimate of the error at 1e-12)";
  } else {
    ref.check = "no estimate: " + why2;
  }
}

// ---- rows ---------------------------------------------------------------------------------

struct Row {
  std::string case_id, variant, scheme;
  Outcome outcome = Outcome::ok;
  std::string reason;
  int pass = 0;
  double error = nan, error_attitude = nan, error_momentum = nan;
  double max_invariant_error = nan;
  std::string max_invariant;
  double cpu_seconds = nan;
  std::int64_t steps = -1, rejected_steps = -1, rhs_evaluations = -1;
  double dt = nan, tol = nan, t_end = nan;
  std::string reference;
  bool state_judged = true;  // false where the final state is ill-conditioned (Criterion::invariants_only)
};

bool evaluate_pass(const Row& row, const Criterion& c, const SchemeInfo& scheme) {
  switch (row.outcome) {
    case Outcome::refused: return !row.reason.empty();
    case Outcome::failed: return c.failure_passes && !row.reason.empty();
    case Outcome::ok: break;
  }
  if (!std::isfinite(row.error) || !std::isfinite(row.max_invariant_error)) return false;
  if (c.zero_time) return row.steps == 0 && row.error <= c.max_error;
  if (c.fixed_one_step && !scheme.properties.adaptive && row.steps != 1) return false;
  if (c.invariants_only) return row.max_invariant_error <= c.max_error;
  return row.error <= c.max_error;
}

Row run_row(const Variant& v, const SchemeInfo& scheme, double budget) {
  Row row;
  row.case_id = v.case_id;
  row.variant = v.variant;
  row.scheme = scheme.name;
  row.t_end = v.t_end;
  if (scheme.properties.adaptive) {
    row.tol = v.tol;
    if (v.first_step > 0.0) row.dt = v.first_step;
  } else {
    row.dt = v.dt;
  }
  row.reference = v.reference.kind;
  row.state_judged = !v.criterion.invariants_only;
  if (v.reference.kind == "converged")
    row.reference += " (" + v.reference.scheme + ", tol " + fmt(v.reference.tol, 3) + ")";

  // What a run reports in the row: the SI run's, or the rescaled run's for a units case.
  auto report_run = [&row](const RunResult& run) {
    row.outcome = run.outcome;
    row.reason = run.reason;
    row.max_invariant_error = run.max_invariant_error;
    row.max_invariant = run.max_invariant;
    row.cpu_seconds = run.cpu_seconds;
    row.steps = run.steps;
    row.rejected_steps = run.rejected_steps;
    row.rhs_evaluations = run.rhs_evaluations;
  };
  const RunResult r = run_scheme(scheme, v.scene, v.t_end, v.dt, v.tol, v.first_step, budget);
  report_run(r);

  if (v.units) {
    const UnitScale& u = v.scale;
    const double sT = u.time;
    const double sPi = u.mass * u.length * u.length / sT;
    const double dt = v.dt * sT, first = v.first_step * sT;
    const RunResult s = run_scheme(scheme, v.scaled, v.t_end * sT, dt, v.tol, first, budget);
    report_run(s);
    if (s.outcome != r.outcome) {
      row.outcome = s.outcome == Outcome::ok ? Outcome::failed : s.outcome;
      row.reason = "outcome differs from the SI run (rescaled: " + std::string(outcome_name(s.outcome)) +
                   (s.reason.empty() ? "" : ": " + s.reason) + "; SI: " + outcome_name(r.outcome) +
                   (r.reason.empty() ? "" : ": " + r.reason) + ")";
    } else if (s.outcome == Outcome::ok && r.have_state && s.have_state) {
      const StateError e = state_error(s.state, r.state, r.max_momentum, sPi);
      const double dt_rel = r.t_final != 0.0 ? std::abs(s.t_final / sT - r.t_final) / std::abs(r.t_final)
                                             : std::abs(s.t_final / sT - r.t_final);
      // Invariant errors are dimensionless already: their difference is compared as it is.
      const double inv_diff = std::abs(s.max_invariant_error - r.max_invariant_error);
      row.error_attitude = e.attitude;
      row.error_momentum = e.momentum;
      row.error = std::max({e.total, dt_rel, inv_diff});
      if (std::isnan(row.error)) row.error = inf;
    }
    row.pass = evaluate_pass(row, v.criterion, scheme) ? 1 : 0;
    return row;
  }

  if (r.outcome == Outcome::ok && r.have_state && v.reference.available) {
    const StateError e = state_error(r.state, v.reference.state, v.reference.momentum_scale);
    row.error = e.total;
    row.error_attitude = e.attitude;
    row.error_momentum = e.momentum;
  } else if (r.outcome == Outcome::ok && r.have_state && !v.reference.available) {
    row.error = nan;
  }
  row.pass = evaluate_pass(row, v.criterion, scheme) ? 1 : 0;
  return row;
}

// ---- the criterion in words ----------------------------------------------------------------

std::string criterion_text(const Criterion& c) {
  if (c.units)
    return "same outcome in both unit systems (refused in both: pass); if ok: final attitude, momentum (relative, "
           "after rescaling), final time and largest invariant error agreeing to " + short_number(c.max_error);
  if (c.zero_time)
    return "ok with 0 steps and the initial state returned to round-off (error <= " + short_number(c.max_error) +
           ": a chart round trip), or refused with a reason";
  std::string s = c.invariants_only
                      ? "ok with a finite final state and invariant errors <= " + short_number(c.max_error) +
                            " (the final state is ill-conditioned here: its error is reported, not judged)"
                      : "ok with a finite error <= " + short_number(c.max_error) + " and finite invariant errors";
  if (c.fixed_one_step) s += " (fixed-step schemes: exactly one step)";
  s += ", or refused with a reason";
  if (c.failure_passes) s += ", or failed with a reason (blow-up, non-convergence, step-size collapse)";
  s += "; never ok with a larger or non-finite error";
  return s;
}

// ---- output ------------------------------------------------------------------------------

std::vector<Column> result_columns() {
  return {{"case", ColumnType::text, ""},
          {"variant", ColumnType::text, ""},
          {"scheme", ColumnType::text, ""},
          {"outcome", ColumnType::text, ""},
          {"reason", ColumnType::text, ""},
          {"pass", ColumnType::integer, ""},
          {"error", ColumnType::real, ""},
          {"error_attitude", ColumnType::real, "rad"},
          {"error_momentum", ColumnType::real, ""},
          {"max_invariant_error", ColumnType::real, ""},
          {"max_invariant", ColumnType::text, ""},
          {"cpu_seconds", ColumnType::real, "s"},
          {"steps", ColumnType::integer, ""},
          {"rejected_steps", ColumnType::integer, ""},
          {"rhs_evaluations", ColumnType::integer, ""},
          {"dt", ColumnType::real, "s"},
          {"tol", ColumnType::real, ""},
          {"t_end", ColumnType::real, "s"},
          {"reference", ColumnType::text, ""},
          {"reference_estimated_error", ColumnType::real, ""}};
}

void append_row(ResultsFile& file, const Row& r, const Variant& v) {
  ResultRow row = file.row();
  row.set("case", r.case_id);
  row.set("variant", r.variant);
  row.set("scheme", r.scheme);
  row.set("outcome", outcome_name(r.outcome));
  row.set("reason", r.reason);
  row.set("pass", r.pass);
  row.set("error", r.error);
  row.set("error_attitude", r.error_attitude);
  row.set("error_momentum", r.error_momentum);
  row.set("max_invariant_error", r.max_invariant_error);
  row.set("max_invariant", r.max_invariant);
  row.set("cpu_seconds", r.cpu_seconds);
  row.set("steps", r.steps);
  row.set("rejected_steps", r.rejected_steps);
  row.set("rhs_evaluations", r.rhs_evaluations);
  row.set("dt", r.dt);
  row.set("tol", r.tol);
  row.set("t_end", r.t_end);
  row.set("reference", r.reference);
  row.set("reference_estimated_error", v.reference.estimated_error);
  file.append(row);
}

/// /case_NN: one group per variant with what it runs, its reference and its criterion.
ResultAttributes case_attributes(const Variant& v) {
  ResultAttributes a;
  a.text["case"] = v.case_id;
  a.text["variant"] = v.variant;
  a.text["scene"] = v.scene_label;
  a.text["description"] = v.description;
  a.text["criterion"] = v.criterion.text;
  a.text["reference_kind"] = v.reference.kind;
  a.text["reference_scheme"] = v.reference.scheme;
  a.text["reference_check"] =
      v.reference.available || v.units ? v.reference.check : "unavailable: " + v.reference.failure;
  a.number["t_end"] = v.t_end;
  a.number["dt"] = v.dt;
  a.number["tol"] = v.tol;
  a.number["first_step"] = v.first_step;
  a.number["reference_tol"] = v.reference.tol;
  a.number["reference_estimated_error"] = v.reference.estimated_error;
  a.number["max_error"] = v.criterion.max_error;
  a.integer["failure_passes"] = v.criterion.failure_passes ? 1 : 0;
  a.integer["invariants_only"] = v.criterion.invariants_only ? 1 : 0;
  a.number_array["initial_angular_momentum"] = {v.scene.initial.Pi.x(), v.scene.initial.Pi.y(),
                                                v.scene.initial.Pi.z()};
  a.number_array["inertia_diagonal"] = {v.scene.inertia(0, 0), v.scene.inertia(1, 1), v.scene.inertia(2, 2)};
  if (v.units) a.number_array["unit_scale_length_mass_time"] = {v.scale.length, v.scale.mass, v.scale.time};
  return a;
}

// ---- the command ---------------------------------------------------------------------------

std::vector<const SchemeInfo*> selected_schemes(const std::string& list) {
  std::vector<const SchemeInfo*> out;
  if (list.empty()) {
    for (const auto& s : integrators::scheme_registry()) out.push_back(&s);
    return out;
  }
  std::set<std::string> seen;
  std::stringstream in(list);
  std::string name;
  while (std::getline(in, name, ',')) {
    const auto b = name.find_first_not_of(" \t");
    const auto e = name.find_last_not_of(" \t");
    name = b == std::string::npos ? "" : name.substr(b, e - b + 1);
    if (name.empty()) throw UsageError("--schemes: empty scheme name in '" + list + "'");
    const SchemeInfo* s = &scheme_by_name(name, "--schemes");
    if (seen.insert(name).second) out.push_back(s);
  }
  if (!list.empty() && list.back() == ',') throw UsageError("--schemes: empty scheme name in '" + list + "'");
  return out;
}

/// An ok row whose answer is wrong beyond doubt: error > 1, or a non-finite error or invariant error.
bool silently_wrong(const Row& r) {
  if (r.outcome != Outcome::ok) return false;
  if (!r.state_judged) return !std::isfinite(r.error) || !(r.max_invariant_error <= 1.0);
  return !(r.error <= 1.0) || !std::isfinite(r.max_invariant_error);
}

struct Tally {
  int runs = 0, ok = 0, refused = 0, failed = 0, pass = 0, wrong = 0;
  std::map<std::string, int> not_passed;  // scheme -> rows
};

int stress(const StressOptions& o) {
  const std::vector<const SchemeInfo*> schemes = selected_schemes(o.schemes);
  const double budget = o.budget.value_or(o.quick ? 2.0 : 10.0);
  if (!(budget > 0.0) || !std::isfinite(budget)) throw UsageError("--budget: must be a finite number > 0");

  std::vector<Variant> variants = build_suite({o.quick, shipped_scenes_dir(o.scenes_dir)});
  for (auto& v : variants) v.criterion.text = criterion_text(v.criterion);

  std::string scheme_list;
  for (const auto* s : schemes) scheme_list += (scheme_list.empty() ? "" : ",") + s->name;
  ResultsFile file(o.out, o.force, result_columns());
  {
    ResultAttributes p;
    p.text["command_line"] = o.command_line;
    p.text["subcommand"] = "stress";
    p.text["schemes"] = scheme_list;
    p.text["criteria"] = "experiments/STRESS.md";
    p.number["budget_seconds"] = budget;
    p.integer["quick"] = o.quick ? 1 : 0;
    p.integer["variants"] = static_cast<std::int64_t>(variants.size());
    file.write_parameters(p);
  }

  interrupt_requested.store(false);
  auto previous_int = std::signal(SIGINT, stress_request_interrupt);
  auto previous_term = std::signal(SIGTERM, stress_request_interrupt);
  const bool progress = !o.quiet && ::isatty(2);

  std::vector<Row> rows;
  std::string stopped;
  const double cpu_start = cpu_now();
  std::size_t k = 0;
  try {
    for (Variant& v : variants) {
      ++k;
      if (progress)
        std::cerr << "\r\033[K[" << k << "/" << variants.size() << "] " << v.case_id << ": " << v.variant
                  << std::flush;
      compute_reference(v, budget);
      char group[32];
      std::snprintf(group, sizeof group, "case_%02zu", k - 1);
      file.write_group(group, case_attributes(v));
      for (const SchemeInfo* s : schemes) {
        Row row = run_row(v, *s, budget);
        append_row(file, row, v);
        rows.push_back(std::move(row));
      }
    }
  } catch (const Interrupted& e) {
    stopped = e.what();
  }
  if (progress) std::cerr << "\r\033[K" << std::flush;
  std::signal(SIGINT, previous_int);
  std::signal(SIGTERM, previous_term);
  const double cpu_total = cpu_now() - cpu_start;

  std::map<std::string, Tally> tally;
  std::vector<std::string> order;
  Tally total;
  for (const Row& r : rows) {
    if (!tally.count(r.case_id)) order.push_back(r.case_id);
    for (Tally* t : {&tally[r.case_id], &total}) {
      ++t->runs;
      t->ok += r.outcome == Outcome::ok;
      t->refused += r.outcome == Outcome::refused;
      t->failed += r.outcome == Outcome::failed;
      t->pass += r.pass;
      t->wrong += silently_wrong(r) ? 1 : 0;
      if (!r.pass) ++t->not_passed[r.scheme];
    }
  }

  ResultAttributes diag;
  diag.text["status"] = stopped.empty() ? "ok" : stopped;
  diag.number["cpu_seconds"] = cpu_total;
  diag.integer["rows"] = static_cast<std::int64_t>(rows.size());
  diag.integer["passes"] = total.pass;
  diag.integer["ok"] = total.ok;
  diag.integer["refused"] = total.refused;
  diag.integer["failed"] = total.failed;
  diag.integer["silently_wrong"] = total.wrong;
  if (!stopped.empty()) {
    file.abandon(diag);
    std::cerr << "lgi: stress " << stopped << " after " << rows.size() << " rows; partial results kept in "
              << file.partial_path() << " and " << file.csv_partial_path() << '\n';
    return exit_run_failed;
  }
  file.finish(diag);

  if (!o.quiet) {
    std::ostringstream s;
    auto line = [&](const std::string& name, const Tally& t) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "%-12s %6d %6d %8d %7d %6d %9d %7d", name.c_str(), t.runs, t.ok, t.refused,
                    t.failed, t.pass, t.runs - t.pass, t.wrong);
      s << buf << '\n';
    };
    s << "case           runs     ok  refused  failed   pass  not_pass  wrong\n";
    for (const auto& c : order) line(c, tally[c]);
    line("total", total);
    s << "cpu_seconds=" << fmt(cpu_total, 4) << " schemes=" << schemes.size() << " variants=" << variants.size()
      << " rows=" << rows.size() << " out=" << file.path() << " csv=" << file.csv_path() << '\n';
    for (const auto& c : order) {
      const Tally& t = tally[c];
      if (t.not_passed.empty()) continue;
      s << "not passed in " << c << ":";
      for (const auto& [scheme, n] : t.not_passed) s << ' ' << scheme << '(' << n << ')';
      s << '\n';
    }
    std::cout << s.str() << std::flush;
  }
  return exit_ok;
}

}  // namespace

Subcommand add_stress_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<StressOptions>();
  auto* sub = app.add_subcommand(
      "stress", "Run the suite of stiff and extreme cases (experiments/STRESS.md) against every scheme that applies");
  sub->add_option("--schemes", o->schemes,
                  "Comma-separated scheme names to run (default: every registered scheme, see `lgi schemes`)");
  sub->add_flag("--quick", o->quick, "Reduced suite (fewer parameters, short t_end) for CI: well under a minute");
  sub->add_option("--scenes-dir", o->scenes_dir,
                  "Folder of the shipped scenes. Default: LGI_SCENES_DIR, else found beside the lgi executable");
  sub->add_option("--out", o->out, "Output file (HDF5); the same table as CSV goes beside it, .csv in place of .h5 (out.h5 -> out.csv)")->required();
  sub->add_flag("--force", o->force, "Overwrite existing output files");
  sub->add_option("--budget", o->budget,
                  "CPU seconds allowed per run before it is stopped and counted as failed (default: 10, --quick: 2)");
  sub->add_flag("--quiet", o->quiet, "Print nothing but errors");
  return {sub, [o, context] {
            o->command_line = context.command_line;
            return stress(*o);
          }};
}

}  // namespace lgi::experiments

// The stress suite's variants, one function per case of STRESS.md.
#include "experiments/commands/stress/stress_suite.hpp"

#include <numbers>
#include <utility>

#include "experiments/io/scene_reader.hpp"
#include "lie/charts.hpp"
#include "lie/so3.hpp"

namespace lgi::experiments::stress {
namespace {

using std::numbers::pi;

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
  if (auto& gravity = s.declared<system::GravityTerm>()) gravity->g = gravity->g * u.length / (sT * sT);
  if (auto& spring = s.declared<system::SpringTerm>()) {
    spring->stiffness = spring->stiffness * sJ / (sT * sT);  // N m/rad = kg m² s⁻²
    spring->damping = spring->damping * sJ / sT;             // N m s/rad = kg m² s⁻¹
  }
  if (auto& drive = s.declared<system::HarmonicDriveTerm>()) {
    drive->torque_amplitude *= (sJ / (sT * sT));
    drive->angular_frequency /= sT;
  }
  // μ·B is an energy (kg m² s⁻²); the field is kept, the moment scaled.
  if (auto& magnetic = s.declared<system::MagneticDipoleTerm>()) magnetic->dipole_moment = magnetic->dipole_moment * sJ / (sT * sT);
  s.initial.Pi = si.initial.Pi * (sJ / sT);  // kg m² s⁻¹
  if (si.t_end) s.t_end = *si.t_end * sT;
  if (s.dt) *s.dt = *si.dt * sT;
  s.file = si.file + " (rescaled)";
  return s;
}

/// The shipped scenes the cases start from, and where the variants go.
struct SuiteBuilder {
  Scene book, top, spring;
  bool quick = false;
  std::vector<Variant> variants;
  void add(Variant v) { variants.push_back(std::move(v)); }

  /// A shipped scene with its label in variant names and its file name.
  struct Base {
    const Scene* scene;
    std::string label, file;
  };
  std::vector<Base> bases() const {
    return {{&book, "book", "dzhanibekov_book_axis2.toml"},
            {&top, "top", "heavy_top_trindade_1.toml"},
            {&spring, "spring", "stiff_damped_spring.toml"}};
  }
};

/// 1. Large steps: h|Ω0| from 0.1 to past π.
void add_large_steps(SuiteBuilder& suite) {
  const Scene& book = suite.book;
  const Scene& top = suite.top;
  const bool quick = suite.quick;
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
      suite.add(std::move(v));
    }
  }
}

/// 2. The separatrix of the book (and of a body whose separatrix is exactly representable).
///    Up to t = 4 the book's flip and the approach to the opposite saddle are well conditioned;
///    exactly on the separatrix the exact orbit then creeps towards the saddle for ever, while
///    any perturbation (the rounding of Π0 included) grows like e^(λt), λ ≈ 4.6 s⁻¹, and flips
///    back: by t = 10 no double-precision method can follow it, and only the invariants are judged.
void add_separatrix(SuiteBuilder& suite) {
  const Scene& book = suite.book;
  const bool quick = suite.quick;
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
    suite.add(std::move(v));
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
    suite.add(std::move(v));
  }
}

/// 3. Exact passage through theta = pi: a heavy top swinging with no spin through the bottom.
void add_theta_pi(SuiteBuilder& suite) {
  const Scene& top = suite.top;
  const bool quick = suite.quick;
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
    suite.add(std::move(v));
  }
}

/// 4. A fast top: spin 1000 rad/s.
void add_fast_top(SuiteBuilder& suite) {
  const Scene& top = suite.top;
  const bool quick = suite.quick;
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
    suite.add(std::move(v));
  }
}

/// 5. Extreme inertia (free bodies, exact reference), at h|Omega0| = 0.01 over 20 rad of rotation
///    (|Omega0| t_end = 20), the resolution at which the ordinary book is resolved to about 1e-4
///    by second-order schemes: what is measured is the effect of the inertia, not of the step.
void add_extreme_inertia(SuiteBuilder& suite) {
  const bool quick = suite.quick;
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
    suite.add(std::move(v));
  }
}

/// 6. Stiffness: the stiff damped spring at h c/J1 from 1 to 1000.
void add_stiffness(SuiteBuilder& suite) {
  const Scene& spring = suite.spring;
  const bool quick = suite.quick;
  std::vector<double> ratios = {1.0, 2.0, 3.0, 10.0, 100.0, 1000.0};
  if (quick) ratios = {1.0, 10.0, 1000.0};
  const double c_over_j = spring.declared<system::SpringTerm>()->damping / spring.inertia(0, 0);  // the fastest mode, 1000 s^-1
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
    suite.add(std::move(v));
  }
}

/// 7. Units: the same scene in mm and mg (and ms).
void add_units(SuiteBuilder& suite) {
  const bool quick = suite.quick;
  struct Unit {
    UnitScale scale;
    std::string label;
  };
  std::vector<Unit> units = {{{1e3, 1e6, 1.0}, "mm mg s"}, {{1e3, 1e6, 1e3}, "mm mg ms"}};
  std::vector<SuiteBuilder::Base> bases = suite.bases();
  if (quick) {
    units = {{{1e3, 1e6, 1e3}, "mm mg ms"}};
    bases.pop_back();  // book and top
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
      suite.add(std::move(v));
    }
  }
}

/// 8. Degenerate runs: t_end = 0, and dt > t_end.
void add_degenerate(SuiteBuilder& suite) {
  for (const auto& b : suite.bases()) {
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
      suite.add(std::move(v));
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
      suite.add(std::move(v));
    }
  }
}

}  // namespace

std::vector<Variant> build_suite(const SuiteSettings& settings) {
  SuiteBuilder suite{shipped(settings.scenes_dir, "dzhanibekov_book_axis2.toml"),
                     shipped(settings.scenes_dir, "heavy_top_trindade_1.toml"),
                     shipped(settings.scenes_dir, "stiff_damped_spring.toml"), settings.quick, {}};
  for (auto add_case : {&add_large_steps, &add_separatrix, &add_theta_pi, &add_fast_top, &add_extreme_inertia,
                        &add_stiffness, &add_units, &add_degenerate})
    add_case(suite);
  return std::move(suite.variants);
}

}  // namespace lgi::experiments::stress

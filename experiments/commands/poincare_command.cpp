// lgi poincare --scene FILE --l L --h H --ics N --t-end T [--axis ...] [--section richter|gamma]
//   [--scheme NAME] [--dt H] [--seed S] [--measure liouville|uniform] [--lyapunov] [--megno [--threshold Y]]
//   [--threads N] [--out FILE.h5] [--force] [--quiet]
// Poincaré sections of a heavy top on one level set (ℓ, h) (experiments/POINCARE.md):
// a sweep (experiments/SWEEPS.md) with N initial states drawn on the level
// set and one event, the section surface, run by the sweep engine
// (commands/sweep/sweep_chunks.hpp); the section coordinates of every
// crossing and, on request, the chaos indicators of every orbit are then
// added to the result file (analysis/poincare_section.hpp) before it is published;
// with --megno, the chaotic fraction and its 95 % Wilson interval (/chaos).
#include <omp.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "experiments/analysis/binomial_interval.hpp"
#include "experiments/analysis/poincare_section.hpp"
#include "experiments/analysis/section_seeds.hpp"
#include "experiments/analysis/sweep_trajectory.hpp"
#include "experiments/cli/work_limits.hpp"
#include "experiments/cli/thread_count.hpp"
#include "experiments/commands/all_commands.hpp"
#include "experiments/commands/poincare_request.hpp"
#include "experiments/cli/interrupt_guard.hpp"
#include "experiments/cli/scheme_lookup.hpp"
#include "experiments/cli/write_failures.hpp"
#include "experiments/commands/atlas/atlas_tables.hpp"
#include "experiments/commands/cardan_atlas.hpp"
#include "experiments/analysis/cardan_section.hpp"
#include "experiments/commands/sweep/sweep_chunks.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/libm_code_path.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/sweep_extra_columns.hpp"
#include "experiments/io/trajectory_observer.hpp"
#include "lgi/build_info.hpp"
#include "integrators/core/loop_support.hpp"

namespace lgi::experiments {
namespace {

using PoincareOptions = PoincareRequest;


constexpr const char* default_so3_scheme = "split-exact@yoshida4";
std::string so3_scheme(const PoincareOptions& o) { return o.scheme.empty() ? default_so3_scheme : o.scheme; }
std::string measure(const PoincareOptions& o) { return o.measure.empty() ? "liouville" : o.measure; }

/// The equivalent `lgi sweep` spec (kept in /parameters spec_toml; the axis
/// of a non-coordinate section axis is set on the parsed spec).
std::string spec_text(const PoincareOptions& o, const std::string& scene_path, double dt, SectionKind kind,
                      const Vec3& e) {
  int component = 1;
  for (int k = 0; k < 3; ++k)
    if (e(k) == 1.0) component = k + 1;
  std::string t = "name = \"lgi poincare\"\nscene = \"" + scene_path + "\"\nscheme = \"" + so3_scheme(o) +
                  "\"\ndt = " + format_exact(dt) + "\nt_end = " + format_exact(o.t_end) + "\nseed = " + std::to_string(o.seed) +
                  "\nsamples = " + std::to_string(o.ics) + "\nmax_events = " + std::to_string(o.max_events) +
                  "\n\n[level_set]\nh = " + format_exact(o.h) + "\nl = " + format_exact(o.l) + "\nmeasure = \"" + measure(o) +
                  "\"\n\n[[event]]\n";
  t += kind == SectionKind::richter ? "quantity = \"gamma_rate\"\n" : "quantity = \"gamma\"\n";
  t += "component = " + std::to_string(component) + "\nname = \"" + (kind == SectionKind::richter ? "richter" : "gamma") +
       "_section\"\n# section axis e = (" + format_exact(e.x()) + ", " + format_exact(e.y()) + ", " + format_exact(e.z()) + ")\n";
  return t;
}

HeavyTopBody heavy_top(const system::Scene& scene) {
  if (!scene.is_free_body() && !scene.declares_only<system::GravityTerm>())
    throw InputError(scene.file + ": lgi poincare needs a heavy top (gravity and no other torque term; a spring, "
                                  "drive or dipole has no level set (l, h))");
  HeavyTopBody body;
  body.J = scene.inertia;
  if (const auto& g = scene.declared<system::GravityTerm>())
    body.weight = scene.mass.value_or(0.0) * g->g * scene.center_of_mass.value_or(Vec3::Zero());
  return body;
}

/// The checks that need no scene (CommandLine::parse runs them first).
void check_flags(const PoincareOptions& o) {
  if (!std::isfinite(o.l)) throw UsageError("--l: must be a finite number");
  if (!std::isfinite(o.h)) throw UsageError("--h: must be a finite number");
  if (!(o.t_end > 0.0) || !std::isfinite(o.t_end)) throw UsageError("--t-end: must be a positive number");
  if (o.seeds.empty() && o.ics < 1) throw UsageError("--ics: must be at least 1 (or give --seeds)");
  if (!o.seeds.empty() && o.ics != 0) throw UsageError("--ics: not with --seeds (the file gives the orbits)");
  if (o.max_events < 1) throw UsageError("--max-events: must be at least 1");
  check_work_limit("--ics", o.ics, max_orbits, "orbits");
  check_work_limit("--max-events", o.max_events, max_section_events, "crossings per orbit");
  if (o.seed > static_cast<std::uint64_t>(INT64_MAX)) throw UsageError("--seed: at most 2^63 - 1 (a TOML integer)");
  if (!o.measure.empty() && !level_measure_from_name(o.measure))
    throw UsageError("--measure: \"" + o.measure + "\": expected liouville or uniform");
  if (!std::isfinite(o.threshold)) throw UsageError("--threshold: must be a finite number");
  if (o.section != "richter" && o.section != "gamma" && o.section != "gamma1" && o.section != "gamma2" &&
      o.section != "gamma3")
    throw UsageError("--section: \"" + o.section + "\": expected richter, gamma, gamma1, gamma2 or gamma3");
  if (o.section.size() == 6 && !o.axis.empty())
    throw UsageError("--axis: --section " + o.section + " sets the axis e" + o.section.substr(5) + " already");
  if (o.scheme.starts_with("cardan-")) return check_cardan_section_scheme(o.scheme);
  const integrators::SchemeInfo& scheme = scheme_by_name(so3_scheme(o), "--scheme");
  if (scheme.properties.adaptive || !scheme.locates_events)
    throw UsageError("--scheme: " + scheme.name + ": lgi poincare takes a fixed-step Lie-group scheme that locates "
                                                  "events (the tangent flow takes the same steps)");
}

void check_options(const PoincareOptions& o, const system::Scene& scene) {
  check_flags(o);
  check_level_not_empty(heavy_top(scene), o.l, o.h, scene.file);
}

/// phi, theta, sheet of every crossing, and the indicators of every orbit.
void add_section_columns(const std::string& path, SectionKind kind, const Vec3& e, const system::Scene& scene) {
  SweepExtraColumns file(path);
  const std::vector<double> g = file.read_real("events", "gamma", 3), p = file.read_real("events", "angular_momentum", 3);
  const std::size_t n = g.size() / 3;
  std::vector<double> phi(n), theta(n);
  std::vector<std::int64_t> sheet(n);
  const Mat3 J_inv = scene.inertia.inverse();
  for (std::size_t r = 0; r < n; ++r) {
    const SectionPoint s =
        section_point(kind, e, Vec3(g[3 * r], g[3 * r + 1], g[3 * r + 2]), Vec3(p[3 * r], p[3 * r + 1], p[3 * r + 2]), J_inv);
    phi[r] = s.phi, theta[r] = s.theta, sheet[r] = s.sheet;
  }
  file.write_real("events", "phi", phi, 1);
  file.write_real("events", "theta", theta, 1);
  file.write_integer("events", "sheet", sheet);
  file.close();
}

/// /chaos, one row: orbits with a finite MEGNO, those above the threshold,
/// their fraction and its 95 % Wilson interval; returns "k/n = f [low, high]".
std::string write_chaotic_fraction(SweepExtraColumns& file, const std::vector<double>& megno, double threshold) {
  std::int64_t n = 0, k = 0;
  for (const double y : megno) {
    if (!std::isfinite(y)) continue;
    ++n;
    k += y > threshold ? 1 : 0;
  }
  const BinomialInterval w = wilson_interval(k, n);
  file.write_real("chaos", "threshold", {threshold}, 1);
  file.write_integer("chaos", "orbits", {n});
  file.write_integer("chaos", "chaotic", {k});
  file.write_real("chaos", "chaotic_fraction", {w.fraction}, 1);
  file.write_real("chaos", "chaotic_fraction_low", {w.low}, 1);
  file.write_real("chaos", "chaotic_fraction_high", {w.high}, 1);
  return format_fraction(k, n);
}

/// The chaos indicators of every orbit, on `threads` threads (each orbit a
/// function of its index alone), written as /sweep columns, and with MEGNO
/// the chaotic fraction (its line in `fraction`).
/// False if a signal stopped it (the orbits left out are not written).
bool add_indicator_columns(const std::string& path, const PoincareOptions& o, const SweepPlan& plan,
                           const system::Scene& scene, double dt, int threads, std::string& fraction) {
  std::vector<double> lyapunov(static_cast<std::size_t>(o.ics)), megno(static_cast<std::size_t>(o.ics));
  std::int64_t computed = 0;
#pragma omp parallel num_threads(threads)
  {
    std::vector<double> flat;
#pragma omp for schedule(dynamic, 1) reduction(+ : computed)
    for (std::int64_t i = 0; i < o.ics; ++i) {
      const auto k = static_cast<std::size_t>(i);
      if (interrupt_requested.load(std::memory_order_relaxed)) continue;
      ++computed;
      try {
        plan.inputs(i, flat);
        const system::State x0 = plan.initial_state(i, scene, flat);
        const OrbitIndicators r = orbit_indicators(scene, x0, o.t_end, dt, o.seed, i);
        lyapunov[k] = r.lyapunov, megno[k] = r.megno;
      } catch (const std::exception&) {  // no initial state: the row's status says why
        lyapunov[k] = megno[k] = std::nan("");
      }
    }
  }
  if (computed < o.ics || interrupt_requested.load()) return false;  // the last orbits may have been cut short
  SweepExtraColumns file(path);
  if (o.lyapunov) file.write_real("sweep", "lyapunov", lyapunov, 1);
  if (o.megno) file.write_real("sweep", "megno", megno, 1);
  if (o.megno) fraction = write_chaotic_fraction(file, megno, o.threshold);
  file.close();
  return true;
}

SweepAttributes attributes(const PoincareOptions& o, const SweepSpec& spec, const system::Scene& scene,
                           const integrators::RunConfig& cfg, const Vec3& e, const ChunkRunStats& run) {
  SweepAttributes a;
  a.parameters = {{"subcommand", "poincare"},     {"scheme", so3_scheme(o)},
                  {"section", o.section},         {"spec_toml", spec.text},
                  {"measure", measure(o)},
                  {"scene_file", scene.file},     {"scene_toml", scene.toml_text},
                  {"lgi_version", build_info::version}, {"compiler", build_info::compiler},
                  {"cxx_flags", build_info::cxx_flags}, {"build_type", build_info::build_type},
                  {"seeds_file", o.seeds}};
  a.numbers = {{"t_end", cfg.t_end}, {"dt", cfg.dt}, {"l", o.l}, {"h", o.h}, {"trajectories", static_cast<double>(o.ics)},
               {"seed", static_cast<double>(o.seed)}, {"threshold", o.threshold}, {"axis_1", e.x()}, {"axis_2", e.y()}, {"axis_3", e.z()}};
  a.provenance = {{"command_line", o.command_line},          {"threads", std::to_string(run.threads)},
                  {"ranks", "1"},                            {"resumed", "no"},
                  {"libm", libm_code_path()},
                  {"utc_start", run.utc_start},              {"utc_end", hdf5::utc_now_iso8601()},
                  {"wall_seconds", format_general(run.wall_seconds, 6)},
                  {"partial_write_seconds", format_general(run.write_seconds, 6)}};
  return a;
}

std::unique_ptr<SweepPartialFile> fresh_partial_file(const PoincareOptions& o, const SweepLayout& layout,
                                                     const std::string& print) {
  const std::string partial = o.out + ".partial";
  hdf5::check_output_target(o.out, o.force);
  hdf5::check_output_target(partial, true);
  if (hdf5::path_exists(partial)) {
    if (!o.force) throw UsageError("--out: " + partial + " exists (an interrupted run; --force replaces it)");
    std::remove(partial.c_str());
  }
  return std::make_unique<SweepPartialFile>(partial, layout, print);
}

/// A Cardan top (docs/cardan.md §9): its own section, orbits and file.
int run_cardan(const PoincareOptions& o, const system::Scene& scene) {
  check_flags(o);
  if (!o.axis.empty()) throw UsageError("--axis: the Cardan top's section is fixed (S = -sin q2 dq2/dt = 0)");
  if (o.section != "richter") throw UsageError("--section: the Cardan top's section is fixed (S = -sin q2 dq2/dt = 0)");
  if (!o.measure.empty())
    throw UsageError("--measure: the Cardan top's level draw is its own (docs/cardan.md §9.2); --measure is for tops on SO(3)");
  if (!o.seeds.empty()) throw UsageError("--seeds: not for a Cardan top (its orbits are drawn on {q1 = 0, H = h, p1 = l})");
  CardanPoincareRequest r;
  r.l = o.l, r.h = o.h, r.t_end = o.t_end, r.dt = o.dt ? *o.dt : scene.dt.value_or(0.0);
  if (const std::string why = integrators::fixed_step_grid_problem(0.0, r.t_end, r.dt); r.dt > 0.0 && !why.empty())
    throw UsageError("--dt: " + why);
  r.ics = o.ics, r.max_events = o.max_events, r.seed = o.seed;
  r.scheme = o.scheme.empty() ? "cardan-rk4" : o.scheme;
  r.out = o.out, r.command_line = o.command_line;
  r.threads = o.threads > 0 ? o.threads : SweepRanks::world().default_threads();
  r.lyapunov = o.lyapunov, r.megno = o.megno, r.force = o.force, r.quiet = o.quiet;
  hdf5::check_output_target(r.out, r.force);
  return run_cardan_poincare(scene, r);
}

int run_poincare(const PoincareOptions& options) {
  PoincareOptions o = options;
  if (SweepRanks::world().size() > 1) throw UsageError("lgi poincare runs on one MPI rank (use --threads)");
  const system::Scene scene = read_scene(o.scene);
  if (scene.suspension) return run_cardan(o, scene);
  if (o.scheme.starts_with("cardan-"))
    throw UsageError("--scheme: " + o.scheme + " integrates the Cardan top; " + scene.file + " has no [suspension]");
  const integrators::SchemeInfo& scheme = scheme_by_name(so3_scheme(o), "--scheme");
  check_options(o, scene);
  const SectionKind kind = o.section.starts_with("gamma") ? SectionKind::gamma : SectionKind::richter;
  // --section gammaK: Γ_K = 0, the axis e_K.
  const std::string axis = o.section.size() == 6 ? "e" + o.section.substr(5) : o.axis;
  const Vec3 e = axis.empty() ? default_section_axis(scene) : parse_section_axis(axis, scene);
  const double dt = o.dt ? *o.dt : scene.dt.value_or(0.0);
  if (!(dt > 0.0)) throw UsageError("--dt: missing, and the scene " + scene.file + " has no [run] dt");
  if (const std::string why = integrators::fixed_step_grid_problem(0.0, o.t_end, dt); !why.empty())
    throw UsageError("--dt: " + why);
  std::vector<SeedState> seeds;
  if (!o.seeds.empty()) {
    seeds = read_section_seeds(o.seeds, heavy_top(scene), kind, e, o.l, o.h);
    o.ics = static_cast<std::int64_t>(seeds.size());
  }
  const std::string scene_path = std::filesystem::absolute(o.scene).lexically_normal().string();
  SweepSpec spec = parse_sweep_spec(spec_text(o, scene_path, dt, kind, e), "lgi-poincare.toml");
  if (kind == SectionKind::richter) spec.events[0].axis = {e.x(), e.y(), e.z()};
  else if (spec.events[0].axis != std::array<double, 3>{e.x(), e.y(), e.z()})
    throw UsageError("--axis: the gamma section takes a body axis e1, e2 or e3");
  for (const SeedState& s : seeds)
    spec.level_set->seeds.push_back({s.gamma.x(), s.gamma.y(), s.gamma.z(), s.Pi.x(), s.Pi.y(), s.Pi.z()});
  const system::AnyModel model = system::make_model(scene);
  if (const std::string why = integrators::unsupported_reason(scheme, model); !why.empty())
    throw UsageError("--scheme: " + why);
  const SweepPlan plan(spec, scene);
  integrators::RunConfig cfg;
  cfg.dt = dt, cfg.t_end = o.t_end;
  SweepLayout layout;
  layout.count = spec.count();
  layout.inputs = plan.input_columns();
  layout.error_names = system::SceneInvariants(scene, model).error_names();
  layout.event_names = {spec.events[0].name};
  // Signals only set the flag from before the first file exists until the results are published (interrupt_guard.hpp).
  const InterruptGuard interrupt_guard;
  auto file = fresh_partial_file(o, layout, "lgi poincare\n" + spec.text + scene.toml_text);
  const int threads = o.threads > 0 ? o.threads : SweepRanks::world().default_threads();
  const ChunkRunStats run = run_chunks(spec, plan, scheme, cfg, layout, file->done(), file.get(), threads, o.quiet,
                                       interrupt_requested, SweepRanks::world());
  const std::string partial = o.out + ".partial", writing = o.out + ".writing";
  const auto stopped = [&](const char* during) {
    std::cerr << "lgi: poincare interrupted by signal" << during << "; the completed orbits are in " << partial << '\n';
    return interrupted_exit_status();
  };
  if (run.interrupted) return stopped("");
  std::remove(writing.c_str());
  file->write_final(writing, attributes(o, spec, scene, cfg, e, run));
  file->close();
  add_section_columns(writing, kind, e, scene);
  std::string fraction;
  if ((o.lyapunov || o.megno) && !add_indicator_columns(writing, o, plan, scene, dt, threads, fraction)) {
    std::remove(writing.c_str());
    return stopped(" while it computed the indicators");
  }
  hdf5::publish(writing, o.out, o.force, "the section is");
  std::remove(partial.c_str());
  if (!o.quiet) {
    std::cout << "poincare: " << o.ics << " orbits of " << scheme.name << " on " << scene.file << " at l = " << format_general(o.l, 6)
              << ", h = " << format_general(o.h, 6) << " (" << measure(o) << " measure), " << file->failures() << " failed, "
              << run.events << " crossings; " << format_general(run.wall_seconds, 3) << " s wall on " << run.threads
              << " threads; wrote " << o.out << '\n';
    if (o.megno) std::cout << "  chaotic (MEGNO > " << format_general(o.threshold, 6) << "): " << fraction << '\n';
  }
  return exit_ok;
}

}  // namespace

int run_poincare_request(const PoincareRequest& request) {
  check_flags(request);
  return run_with_write_failures_as_run_errors([&] { return run_poincare(request); });
}

Subcommand add_poincare_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<PoincareOptions>();
  auto* sub = app.add_subcommand("poincare",
                                 "Poincare sections of a heavy top on the level set (l, h): Richter's section "
                                 "d(Gamma.e)/dt = 0, crossings located by the sweep engine, MEGNO and Lyapunov "
                                 "exponents from the tangent flow (experiments/POINCARE.md)");
  sub->add_option("--scene", o->scene, "Scene file (a heavy top: gravity alone, a free body, or a Cardan top: "
                                       "docs/cardan.md)")->required();
  sub->add_option("--l", o->l, "l = Pi.Gamma, the vertical angular momentum")->required();
  sub->add_option("--h", o->h, "h, the energy")->required();
  sub->add_option("--ics", o->ics, "Initial conditions (orbits) drawn on the level set (not with --seeds)");
  sub->add_option("--seeds", o->seeds,
                  "CSV of section points phi,theta,sheet or states gamma_1..3,angular_momentum_1..3 on the level: "
                  "one orbit from each row, instead of --ics draws (experiments/POINCARE.md)");
  sub->add_option("--t-end", o->t_end, "Time span of each orbit")->required();
  sub->add_option("--axis", o->axis,
                  "Section axis e: e1, e2, e3, com or x,y,z (default: e3 for a Lagrange top or the free body, "
                  "chi/|chi| otherwise)");
  sub->add_option("--section", o->section,
                  "richter (d(Gamma.e)/dt = 0), gamma (Gamma.e = 0, e a body axis) or gamma1, gamma2, gamma3 "
                  "(Gamma_k = 0)")->capture_default_str();
  sub->add_option("--scheme", o->scheme,
                  "Fixed-step scheme (lgi schemes; default split-exact@yoshida4, and cardan-rk4 for a Cardan top)");
  sub->add_option("--dt", o->dt, "Step (default: the scene's [run] dt)");
  sub->add_option("--seed", o->seed, "Seed of the level-set draws and of the tangent vectors")->capture_default_str();
  sub->add_option("--measure", o->measure,
                  "Density of the draws on the level set: liouville (the phase-space measure, the default) or "
                  "uniform (Gamma uniform on the sphere, lgi's draw before; docs/atlas.md §6)");
  sub->add_option("--max-events", o->max_events, "Crossings kept per orbit")->capture_default_str();
  sub->add_flag("--lyapunov", o->lyapunov, "Add /sweep/lyapunov: the maximal Lyapunov exponent (tangent flow)");
  sub->add_flag("--megno", o->megno,
                "Add /sweep/megno: MEGNO <Y> at t_end (tangent flow), and /chaos: the chaotic fraction with its 95 % "
                "Wilson interval");
  sub->add_option("--threshold", o->threshold, "With --megno: an orbit is chaotic where MEGNO <Y>(t_end) exceeds this")
      ->capture_default_str();
  sub->add_option("--threads", o->threads, "OpenMP threads (default: all cores; at most 64 per core)")->check(thread_count_check());
  sub->add_option("--out", o->out, "Output file (HDF5); required")->required();
  sub->add_flag("--force", o->force, "Replace an existing output file");
  sub->add_flag("--quiet", o->quiet, "No progress line and no summary");
  sub->footer(exit_status_help);
  return {sub,
          [o, context] {
            o->command_line = context.command_line;
            return run_with_write_failures_as_run_errors([&] { return run_poincare(*o); });
          },
          [o] { check_flags(*o); }};
}

}  // namespace lgi::experiments

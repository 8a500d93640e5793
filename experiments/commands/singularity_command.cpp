// lgi singularity: the Euler-angle singularity study (experiments/SINGULARITY.md).
//
// Two scenes: heavy_top_trindade_singular (the c.o.m. swings through the
// bottom, θ passing within nanoradians of π at every swing) and
// heavy_top_trindade_4 (the slow top falls toward θ = π). On each: every
// baseline (the euler-zxz ones also with the singularity guard turned off,
// to show what Trindade & Sampaio's integration did), several Lie-group
// schemes, and a tight reference (singularity_runs). Per run: outcome,
// counts, CPU time, the accepted step sizes, the centre of mass R χ on a
// common time grid, and for Euler angles the raw ψ, θ, φ, θ̇ at every
// accepted step; written by singularity_output.
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "experiments/commands/all_commands.hpp"
#include "experiments/cli/interrupt_guard.hpp"
#include "experiments/cli/step_settings.hpp"
#include "experiments/commands/singularity/singularity_output.hpp"
#include "experiments/commands/singularity/singularity_runs.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/results_file.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/scenes_location.hpp"
#include "experiments/io/trajectory_observer.hpp"  // interrupt_requested
#include "integrators/core/loop_support.hpp"

namespace lgi::experiments {
namespace {
// This file's own namespace: its `using namespace` below does not reach the next
// file of a unity batch (experiments/CMakeLists.txt).
namespace singularity_cli {

using namespace singularity;

struct SingularityOptions {
  std::string out;
  std::optional<double> tol;
  std::optional<double> dt;
  bool quick = false;
  bool force = false;
  bool quiet = false;
  std::string scenes_dir;  // --scenes-dir; empty: found beside the executable
  std::string command_line;
};

/// One scene as the study runs it: the flags, then the scene's [run], then 1e-8 / 1e-3.
StudyScene study_scene(const system::Scene& scene, const SceneCase& sc, const SingularityOptions& o) {
  StudyScene s;
  s.scene = &scene;
  s.model = system::make_model(scene);
  const double scene_t_end = resolve_t_end(std::nullopt, scene, /*allow_zero=*/false);
  s.t_end = o.quick ? std::min(sc.t_end_quick, scene_t_end) : scene_t_end;
  s.tol = o.tol ? *o.tol : scene.tol.value_or(1e-8);
  s.dt = o.dt ? *o.dt : scene.dt.value_or(1e-3);
  s.chi = scene.center_of_mass.value_or(Vec3::Zero());
  s.J_inv = system::make_inertia(scene.inertia).J_inv;
  const auto G = static_cast<std::size_t>(std::llround(s.t_end / grid_spacing)) + 1;
  for (std::size_t i = 0; i < G; ++i) s.grid.push_back(std::min(s.t_end, static_cast<double>(i) * grid_spacing));
  return s;
}

void print_run(const std::string& key, const RunRecord& r) {
  const Method& m = r.method;
  std::cout << key << ' ' << m.name << " outcome=" << (r.stats.ok ? "ok" : "failed")
            << " t_final=" << format_general(r.stats.t_final) << " steps=" << r.stats.steps
            << " rejected=" << r.stats.work.rejected_steps << " rhs_evaluations=" << r.stats.work.rhs_evaluations
            << " cpu_seconds=" << format_general(r.cpu_seconds, 3) << " h_min=" << format_general(r.h_min, 3)
            << " com_max_deviation=" << format_general(r.com_max_deviation, 3);
  if (is_euler(m)) std::cout << " min_abs_sin_theta=" << format_general(r.min_abs_sin_theta, 3);
  std::cout << '\n';
  if (!r.stats.ok) std::cout << "  status: " << r.stats.status << '\n';
}

void write_parameters(H5& h5, const SingularityOptions& o, double tol, double dt, const std::string& csv,
                      const std::string& utc, const std::string& status) {
  const hdf5::Handle pg = h5.group("/parameters");
  h5.text(pg.get(), "status", status);
  h5.text(pg.get(), "command", "singularity");
  h5.text(pg.get(), "command_line", o.command_line);
  h5.number(pg.get(), "tol", tol);
  h5.number(pg.get(), "dt", dt);
  h5.integer(pg.get(), "quick", o.quick ? 1 : 0);
  h5.number(pg.get(), "grid_spacing", grid_spacing);
  h5.text(pg.get(), "reference_scheme", reference_scheme);
  h5.number(pg.get(), "reference_tol", reference_tol);
  h5.number(pg.get(), "euler_singular_threshold", bl::default_euler_singular_threshold);
  h5.number(pg.get(), "euler_fixed_step_resolution", bl::default_euler_fixed_step_resolution);
  h5.text(pg.get(), "csv_file", csv);
  for (const auto& [k, v] : hdf5::default_provenance(utc)) h5.text(pg.get(), k.c_str(), v);
}

void check_flags(const SingularityOptions& o) {
  if (o.out.empty()) throw UsageError("--out: an output file is required");
  if (o.tol && !(*o.tol > 0.0 && std::isfinite(*o.tol))) throw UsageError("--tol: must be a finite number > 0");
  if (o.dt && !(*o.dt > 0.0 && std::isfinite(*o.dt))) throw UsageError("--dt: must be a finite number > 0");
}

int singularity_command(const SingularityOptions& o) {
  check_flags(o);
  const std::string csv = results_csv_path(o.out);
  for (const std::string& path : {o.out, csv}) hdf5::check_output_target(path, o.force);

  const std::string scenes_dir = shipped_scenes_dir(o.scenes_dir);
  const std::vector<SceneCase> cases = {
      {"trindade_singular", scenes_dir + "/heavy_top_trindade_singular.toml", 2.5},
      {"trindade_4", scenes_dir + "/heavy_top_trindade_4.toml", 4.0},
  };

  // Every scene is read before <out>.partial exists: a missing one is bad input (exit 2, nothing written).
  std::vector<system::Scene> scenes;
  for (const SceneCase& c : cases) scenes.push_back(read_scene(c.file));
  // The fixed-step runs' grid (issue 50): a step that cannot advance time is bad input, not a failed row.
  for (std::size_t ci = 0; ci < cases.size(); ++ci) {
    const StudyScene sc = study_scene(scenes[ci], cases[ci], o);
    if (const std::string why = integrators::fixed_step_grid_problem(0.0, sc.t_end, sc.dt); !why.empty())
      throw UsageError(std::string(o.dt ? "--dt: " : "--dt ([run] dt of " + scenes[ci].file + "): ") + why);
  }

  const std::string partial = o.out + ".partial";
  // Signals only set the flag from before the first file exists until the results are published (interrupt_guard.hpp).
  const InterruptGuard interrupt_guard;
  H5 h5(partial);
  const std::string utc = hdf5::utc_now_iso8601();
  hdf5::write_h5md_metadata(h5.file(), /*units_module=*/false, h5.fail());
  h5.group("/scenes");

  std::vector<std::vector<RunRecord>> all(cases.size());
  std::vector<SummaryRow> rows;
  double tol_used = 0.0, dt_used = 0.0;
  // Ctrl-C / SIGTERM: every run reads the flag every step (RunConfig::stop); the run it cuts (or the
  // scene's reference) is dropped and the runs finished before it are kept.
  bool stopped = false;  // a signal came before every run was done
  const auto interrupted = [&stopped] { return stopped = stopped || interrupt_requested.load(); };
  for (std::size_t ci = 0; ci < cases.size() && !interrupted(); ++ci) {
    const StudyScene sc = study_scene(scenes[ci], cases[ci], o);
    tol_used = sc.tol;
    dt_used = sc.dt;
    const std::optional<std::vector<double>> reference = reference_center_of_mass(sc, &interrupt_requested);
    if (!reference) {
      stopped = true;
      break;
    }
    for (const Method& m : study_methods(o.quick, sc.model)) {
      if (interrupted()) break;
      std::optional<RunRecord> run = run_study_method(m, sc, *reference, &interrupt_requested);
      if (!run) {
        stopped = true;
        break;
      }
      all[ci].push_back(std::move(*run));
      if (!o.quiet) print_run(cases[ci].key, all[ci].back());
    }
    write_scene_group(h5, cases[ci].key, sc, *reference, all[ci]);
    for (const RunRecord& r : all[ci]) rows.push_back({cases[ci].key, &r, sc.tol, sc.dt});
    h5.flush();
  }
  write_results_table(h5, rows);
  write_parameters(h5, o, tol_used, dt_used, csv, utc, stopped ? integrators::interrupted_status : "ok");
  h5.close();
  if (stopped) {
    std::cerr << "lgi: singularity " << integrators::interrupted_status << " after " << rows.size()
              << " runs; they are kept in " << partial << '\n';
    return interrupted_exit_status();
  }
  write_results_csv(csv, rows, o.force);
  hdf5::publish(partial, o.out, o.force, "the study is");
  if (!o.quiet) std::cout << "wrote " << o.out << " and " << csv << '\n';
  return exit_ok;
}

}  // namespace singularity_cli
}  // namespace

Subcommand add_singularity_subcommand(CLI::App& app, const CommandContext& context) {
  using namespace singularity_cli;
  auto o = std::make_shared<SingularityOptions>();
  auto* sub = app.add_subcommand(
      "singularity",
      "The Euler-angle singularity study: every baseline and several Lie-group schemes on "
      "heavy_top_trindade_singular and heavy_top_trindade_4 (layout: experiments/SINGULARITY.md)");
  sub->add_option("--out", o->out,
                  "Output file (HDF5); the same table as CSV goes beside it, .csv in place of .h5 (out.h5 -> out.csv)")
      ->required();
  sub->add_option("--tol", o->tol,
                  "Tolerance of the controlled steppers and adaptive schemes. Default: the scenes' [run] tol (1e-8)");
  sub->add_option("--dt", o->dt, "Step of the fixed-step steppers and schemes. Default: the scenes' [run] dt (1e-3)");
  sub->add_flag("--quick", o->quick, "A few methods over the first swings only (a CI check, seconds)");
  sub->add_option("--scenes-dir", o->scenes_dir,
                  "Folder of the shipped scenes. Default: LGI_SCENES_DIR, else found beside the lgi executable");
  sub->add_flag("--force", o->force, "Overwrite existing output files");
  sub->add_flag("--quiet", o->quiet, "Print nothing but errors");
  sub->footer(exit_status_help);
  return {sub,
          [o, context] {
            o->command_line = context.command_line;
            return singularity_command(*o);
          },
          [o] { check_flags(*o); }};
}

}  // namespace lgi::experiments

// lgi sweep --spec FILE.toml --out FILE.h5 [--threads N] [--simd ISA] [--resume] [--quiet] [--force]
// Many trajectories of one scheme on a family of scenes and initial states
// (experiments/SWEEPS.md): the spec and its scene are read and checked, the
// trajectories are cut into chunks of consecutive indices, the chunks run on
// OpenMP threads (and MPI ranks, sweep/sweep_ranks.hpp), each completed chunk
// goes to <out>.partial, and the final file is written from it at the end.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "experiments/analysis/sweep_trajectory.hpp"
#include "experiments/cli/cardan_simulation.hpp"
#include "experiments/cli/thread_count.hpp"
#include "experiments/commands/all_commands.hpp"
#include "experiments/commands/sweep_request.hpp"
#include "experiments/cli/interrupt_guard.hpp"
#include "experiments/cli/scheme_lookup.hpp"
#include "experiments/cli/sweep_progress.hpp"
#include "experiments/commands/sweep/sweep_chunks.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/h5md_writer.hpp"
#include "experiments/io/libm_code_path.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/trajectory_observer.hpp"
#include "integrators/ensemble/ensemble.hpp"
#include "integrators/core/loop_support.hpp"
#include "lgi/build_info.hpp"

namespace lgi::experiments {
namespace {

struct SweepOptions {
  std::string spec, out;
  int threads = 0;
  std::string simd = "auto";  // the ensemble path (docs/ensemble.md)
  bool resume = false, quiet = false, force = false;
  std::string command_line;
};

/// dt or tol from the spec, else the scene's [run]; t_end likewise.
integrators::RunConfig sweep_run_config(const SweepSpec& spec, const system::Scene& scene,
                                        const integrators::SchemeInfo& scheme) {
  integrators::RunConfig cfg;
  const bool adaptive = scheme.properties.adaptive;
  const std::string where = spec.file + ": ";
  if (adaptive && spec.dt) throw InputError(where + "dt: " + scheme.name + " is adaptive; give tol");
  if (!adaptive && spec.tol) throw InputError(where + "tol: " + scheme.name + " takes a fixed step; give dt");
  if (adaptive) {
    const auto tol = spec.tol ? spec.tol : scene.tol;
    if (!tol) throw InputError(where + "tol: missing, and the scene " + scene.file + " has no [run] tol");
    cfg.tol = *tol;
  } else {
    const auto dt = spec.dt ? spec.dt : scene.dt;
    if (!dt) throw InputError(where + "dt: missing, and the scene " + scene.file + " has no [run] dt");
    cfg.dt = *dt;
  }
  const auto t_end = spec.t_end ? spec.t_end : scene.t_end;
  if (!t_end || !(*t_end > 0.0)) throw InputError(where + "t_end: missing, and the scene " + scene.file + " has no [run] t_end > 0");
  cfg.t_end = *t_end;
  cfg.save_every = spec.monitor_every;
  // Refused up front (issue 50): otherwise every row fails and the sweep still exits 0.
  if (!adaptive)
    if (const std::string why = integrators::fixed_step_grid_problem(cfg.t0, cfg.t_end, cfg.dt); !why.empty())
      throw InputError(where + "dt: " + why);
  return cfg;
}

/// The spec's scheme for the scene's state space (a cardan-* scheme on a Cardan scene).
const integrators::SchemeInfo& sweep_scheme(const SweepSpec& spec, const system::Scene& scene) {
  try {
    return scheme_for_scene(scene, spec.scheme, "scheme");
  } catch (const UsageError& e) {
    throw InputError(spec.file + ": " + e.what());
  }
}

/// A Cardan scene's initial state is on T³ × ℝ³ (its [initial] cardan_angles
/// and cardan_rates): the SO(3) initial keys and the (ℓ, h) level sets do not
/// apply to it (docs/cardan.md §7).
void check_cardan_spec(const SweepSpec& spec, const system::Scene& scene) {
  if (!is_cardan_scene(scene)) return;
  if (spec.level_set)
    throw InputError(spec.file + ": level_set: draws SO(3) states; the scene " + scene.file +
                     " is a Cardan top (state on T^3 x R^3): vary its suspension, body or term keys");
  for (const auto& v : spec.vary)
    if (v.initial_state())
      throw InputError(spec.file + ": vary: key \"initial." + v.name + "\" sets an SO(3) state; the scene " +
                       scene.file + " is a Cardan top (state on T^3 x R^3): vary its suspension, body or term keys");
}

/// --simd: the instruction set of the ensemble path (auto: the widest this
/// CPU has; off: one trajectory at a time). The rows are the same for any.
void select_simd(const std::string& simd) {
  namespace ensemble = integrators::ensemble;
  if (simd == "auto") return ensemble::set_sweep_isa(ensemble::best_isa());
  if (simd == "off") return ensemble::set_sweep_isa(std::nullopt);
  const auto isa = ensemble::parse_isa(simd);
  std::string available;
  for (const auto a : ensemble::available_isas()) available += std::string(", ") + ensemble::isa_name(a);
  if (!isa) throw UsageError("--simd: unknown '" + simd + "' (auto, off" + available + ")");
  if (!ensemble::isa_available(*isa))
    throw UsageError("--simd: " + simd + " is not available on this CPU (auto, off" + available + ")");
  ensemble::set_sweep_isa(*isa);
}

/// What the ensemble path used: "avx512 (16 lanes)", or "off".
/// The instruction set chosen for the ensemble and, where the sweep's scheme
/// has no kernel for its scene (docs/ensemble.md), that it was not used and why.
std::string simd_used(const system::Scene& scene, const integrators::SchemeInfo& scheme,
                      const integrators::RunConfig& cfg) {
  const auto isa = integrators::ensemble::sweep_isa();
  if (!isa) return "off";
  std::string used = std::string(integrators::ensemble::isa_name(*isa)) + " (" +
                     std::to_string(integrators::ensemble::isa_lanes(*isa)) + " lanes)";
  std::string why = integrators::ensemble::unsupported_reason(scheme, system::make_model(scene));
  if (why.empty() && (scheme.properties.adaptive || !(cfg.dt > 0.0))) why = "no ensemble for adaptive steps";
  return why.empty() ? used : used + "; not used: " + why;
}

std::string fingerprint(const SweepSpec& spec, const system::Scene& scene, const integrators::SchemeInfo& scheme) {
  return std::string("lgi ") + build_info::version + "\nscheme " + scheme.name + "\n--- spec\n" + spec.text +
         "\n--- scene\n" + scene.toml_text;
}

SweepAttributes final_attributes(const SweepSpec& spec, const system::Scene& scene, const integrators::RunConfig& cfg,
                                 const integrators::SchemeInfo& scheme, const SweepOptions& o, const ChunkRunStats& run) {
  SweepAttributes a;
  a.parameters = {{"subcommand", "sweep"},        {"scheme", scheme.name},
                  {"spec_file", spec.file},       {"spec_toml", spec.text},
                  {"scene_file", scene.file},     {"scene_toml", scene.toml_text},
                  {"lgi_version", build_info::version}, {"compiler", build_info::compiler},
                  {"cxx_flags", build_info::cxx_flags}, {"build_type", build_info::build_type}};
  a.numbers = {{"t_end", cfg.t_end}, {"trajectories", static_cast<double>(spec.count())}};
  if (cfg.dt > 0.0) a.numbers.push_back({"dt", cfg.dt});
  if (cfg.tol > 0.0) a.numbers.push_back({"tol", cfg.tol});
  a.provenance = {{"command_line", o.command_line},
                  {"threads", std::to_string(run.threads)},
                  {"simd", simd_used(scene, scheme, cfg)},
                  {"libm", libm_code_path()},
                  {"ranks", std::to_string(run.ranks)},
                  {"resumed", o.resume ? "yes" : "no"},
                  {"utc_start", run.utc_start},
                  {"utc_end", hdf5::utc_now_iso8601()},
                  {"wall_seconds", format_general(run.wall_seconds, 6)},
                  {"partial_write_seconds", format_general(run.write_seconds, 6)}};
  return a;
}

/// <out>.partial, new or (--resume) the one an interrupted run left.
std::unique_ptr<SweepPartialFile> open_partial_file(const SweepOptions& o, const SweepLayout& layout,
                                                    const std::string& print) {
  const std::string partial = o.out + ".partial";
  if (!o.resume && hdf5::path_exists(partial))
    throw UsageError("--out: " + partial + " exists (an interrupted sweep): finish it with --resume, or remove it");
  if (o.resume && !hdf5::path_exists(partial))
    throw UsageError("--resume: there is no " + partial + " to resume" +
                     (hdf5::path_exists(o.out) ? " (" + o.out + " is complete)" : ""));
  hdf5::check_output_target(o.out, o.force);
  hdf5::check_output_target(partial, true);
  if (o.resume) return std::make_unique<SweepPartialFile>(partial, layout, print, true);
  return std::make_unique<SweepPartialFile>(partial, layout, print);
}

int run_sweep(const SweepOptions& o) {
  select_simd(o.simd);
  const SweepSpec spec = read_sweep_spec(o.spec);
  const system::Scene scene = read_scene(spec.scene_path);
  check_cardan_spec(spec, scene);
  const integrators::SchemeInfo& scheme = sweep_scheme(spec, scene);
  const integrators::RunConfig cfg = sweep_run_config(spec, scene, scheme);
  if (!spec.events.empty() && !scheme.locates_events)
    throw InputError(spec.file + ": event: " + scheme.name +
                     " does not locate events (the baselines keep their own loop); use a Lie-group scheme");
  const system::AnyModel model = system::make_model(scene);
  if (const std::string why = is_cardan_scene(scene) ? "" : integrators::unsupported_reason(scheme, model); !why.empty())
    throw InputError(spec.file + ": scheme: " + why + "; the scene " + scene.file + " is not one");
  const SweepPlan plan(spec, scene);

  SweepLayout layout;
  layout.count = spec.count();
  layout.inputs = plan.input_columns();
  // A Cardan sweep's columns: H, and p1 (NaN in rows where it is no integral).
  layout.error_names = is_cardan_scene(scene) ? std::vector<std::string>{"energy", "cardan_momentum_1"}
                                              : system::SceneInvariants(scene, model).error_names();
  for (const auto& e : spec.events) layout.event_names.push_back(e.name);
  layout.trajectories = spec.trajectory_every > 0;

  const std::string partial = o.out + ".partial", writing = o.out + ".writing";
  // Signals only set the flag from before the first file exists until the results are published (interrupt_guard.hpp).
  const InterruptGuard interrupt_guard;
  SweepRanks& ranks = SweepRanks::world();
  // Rank 0 alone checks and opens the files; the others learn the outcome.
  std::unique_ptr<SweepPartialFile> file;
  std::vector<char> done;
  std::exception_ptr refused;
  if (ranks.root()) {
    try {
      file = open_partial_file(o, layout, fingerprint(spec, scene, scheme));
      done = file->done();
    } catch (...) {
      refused = std::current_exception();
    }
  }
  if (ranks.broadcast(refused ? 1 : 0) != 0) {
    if (refused) std::rethrow_exception(refused);
    return exit_bad_input;  // rank 0 says why
  }
  ranks.broadcast(done);
  const int threads = o.threads > 0 ? o.threads : ranks.default_threads();
  const ChunkRunStats run = run_chunks(spec, plan, scheme, cfg, layout, std::move(done), file.get(), threads, o.quiet,
                                       interrupt_requested, ranks);
  if (!ranks.root()) return run.interrupted ? interrupted_exit_status() : exit_ok;
  const auto completed = std::count(file->done().begin(), file->done().end(), char{1});
  if (run.interrupted || completed < layout.count) {
    std::cerr << "lgi: sweep " << (run.interrupted ? "interrupted by signal" : "incomplete (a rank stopped)") << "; "
              << completed << " of " << layout.count << " trajectories kept in " << partial
              << " (finish with --resume)\n";
    return run.interrupted ? interrupted_exit_status() : exit_run_failed;
  }
  std::remove(writing.c_str());
  file->write_final(writing, final_attributes(spec, scene, cfg, scheme, o, run));
  file->close();
  hdf5::publish(writing, o.out, o.force, "the sweep is");
  std::remove(partial.c_str());
  if (!o.quiet) {
    std::cout << "sweep: " << layout.count << " trajectories of " << scheme.name << " on " << scene.file << ", "
              << file->failures() << " failed, " << run.events << " crossings; " << format_general(run.cpu_seconds, 3)
              << " s CPU in trajectories, " << format_general(run.wall_seconds, 3) << " s wall on " << run.threads
              << " threads x " << run.ranks << " ranks; wrote " << o.out << '\n';
  }
  return exit_ok;
}

}  // namespace

int run_sweep_request(const SweepRequest& request) {
  SweepOptions o;
  o.spec = request.spec;
  o.out = request.out;
  o.threads = request.threads;
  o.force = request.force;
  o.quiet = request.quiet;
  o.command_line = request.command_line;
  return run_sweep(o);
}

Subcommand add_sweep_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<SweepOptions>();
  auto* sub = app.add_subcommand(
      "sweep",
      "Many trajectories at once: a base scene, a scheme and what varies (initial states on a grid, at random or "
      "on a level set; any scene key), with events; OpenMP threads and MPI ranks, resumable (experiments/SWEEPS.md)");
  sub->add_option("--spec", o->spec, "Sweep spec (TOML; experiments/SWEEPS.md, examples in experiments/sweeps/)")
      ->required();
  sub->add_option("--out", o->out, "Output file (HDF5); <out>.partial while it runs")->required();
  sub->add_option("--threads", o->threads, "OpenMP threads (default: all cores; at most 64 per core)")->check(thread_count_check());
  sub->add_option("--simd", o->simd,
                  "Trajectories in SIMD lanes where the scheme has an ensemble kernel (docs/ensemble.md): auto, off "
                  "(one at a time), sse2, avx2, avx512; the results are the same bit for bit")
      ->capture_default_str();
  sub->add_flag("--resume", o->resume, "Finish an interrupted sweep from <out>.partial (same spec and arguments)");
  sub->add_flag("--force", o->force, "Replace an existing output file");
  sub->add_flag("--quiet", o->quiet, "No progress line and no summary");
  sub->footer(exit_status_help);
  return {sub, [o, context] {
            o->command_line = context.command_line;
            SweepRanks& ranks = SweepRanks::world();
            if (ranks.size() == 1) return run_sweep(*o);
            try {
              return run_sweep(*o);
            } catch (const InputError& e) {  // every rank read the same input: rank 0 alone says why
              if (ranks.root()) throw;
              return static_cast<int>(exit_bad_input);
            } catch (const UsageError& e) {
              if (ranks.root()) throw;
              return static_cast<int>(exit_bad_input);
            } catch (const OutputWriteError& e) {  // a failed write during the run: the ranks end as one
              std::cerr << "lgi: rank " << ranks.rank() << ": " << e.what() << '\n';
              ranks.abort(exit_run_failed);
            } catch (const OutputFileError& e) {  // rank 0 refused the output or the resume file before the run
              if (ranks.root()) throw;
              return static_cast<int>(exit_bad_input);
            } catch (const std::exception& e) {  // during the run: the other ranks cannot finish
              std::cerr << "lgi: rank " << ranks.rank() << ": " << e.what() << '\n';
              ranks.abort(exit_run_failed);
            }
          }};
}

}  // namespace lgi::experiments

// lgi equilibria --scene FILE [--l L] [--samples N] --out FILE.h5 [--force] [--quiet]
// lgi bifurcation --scene FILE [--samples N] --out FILE.h5: the same without --l
// The relative equilibria (Staude's permanent rotations) of a scene's heavy
// top and their stability (analysis/relative_equilibria.hpp; layout and
// meaning: experiments/EQUILIBRIA.md).
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "experiments/analysis/kovalevskaya_diagram.hpp"
#include "experiments/analysis/relative_equilibria.hpp"
#include "experiments/cli/interrupt_guard.hpp"
#include "experiments/cli/sweep_progress.hpp"
#include "experiments/cli/work_limits.hpp"
#include "experiments/commands/all_commands.hpp"
#include "experiments/cli/grid_range.hpp"
#include "experiments/cli/run_options.hpp"
#include "experiments/commands/atlas/atlas_tables.hpp"
#include "experiments/commands/cardan_atlas.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/hdf5_support.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/table_file.hpp"
#include "experiments/io/trajectory_observer.hpp"  // interrupt_requested
#include "lgi/build_info.hpp"

namespace lgi::experiments {
namespace {

struct EquilibriaOptions {
  std::string scene, out;
  std::optional<double> l;
  std::vector<double> appelrot;  // lgi bifurcation --appelrot: the Kovalevskaya (h, k) diagram at these l
  std::string appelrot_h;
  int samples = 400;
  std::optional<double> omega_max;  // the Cardan top's diagram (docs/cardan.md §9)
  bool force = false, quiet = false;
  std::string command_line, subcommand = "equilibria";
};

void print_row(const RelativeEquilibrium& e) {
  std::printf("branch=%d omega=%.6g gamma=(%.6g, %.6g, %.6g) l=%.6g h=%.6g stability=%s g1=%.6g g2=%.6g "
              "nonlinearly_stable=%s%s%s\n",
              e.branch, e.omega, e.gamma.x(), e.gamma.y(), e.gamma.z(), e.l, e.h, stability_name(e.stability), e.g1,
              e.g2, e.nonlinearly_stable ? "yes" : "no", e.fold ? " fold" : "", e.class_change ? " class_change" : "");
}

void check_flags(const EquilibriaOptions& o) {
  if (o.l && !std::isfinite(*o.l)) throw UsageError("--l: must be a finite number");
  if (o.samples < 3) throw UsageError("--samples: must be at least 3");
  check_work_limit("--samples", o.samples, max_branch_samples, "points per branch");
  for (const double l : o.appelrot)
    if (!std::isfinite(l)) throw UsageError("--appelrot: the values of l must be finite numbers");
  if (!o.appelrot_h.empty()) {
    if (o.appelrot.empty()) throw UsageError("--appelrot-h: only with --appelrot");
    parse_grid_range(o.appelrot_h, "--appelrot-h");
  }
}

/// --appelrot: the Kovalevskaya top's (h, k) diagram (analysis/kovalevskaya_diagram.hpp),
/// the range of k at --appelrot-h (default: h/(J3 c) from -1.1 to 5 in steps of 0.05).
std::vector<TableGroup> appelrot(const EquilibriaOptions& o, const system::Scene& scene, const HeavyTopBody& body) {
  if (o.appelrot.empty()) return {};
  const auto scale = kovalevskaya_scale(body);
  if (!scale)
    throw UsageError("--appelrot: " + scene.file +
                     " is not a Kovalevskaya top (J = J3 diag(2, 2, 1), centre of mass on e1)");
  const std::vector<double> hs = appelrot_energies(*scale, o.appelrot_h);
  // Progress on stderr (cli/sweep_progress.hpp; issue 50, item 8): the curves take seconds per l.
  // A signal stops after the current l; the command then writes nothing.
  SweepProgress progress(o.quiet, static_cast<std::int64_t>(o.appelrot.size()), 0, o.subcommand.c_str(), "values of l");
  auto groups = appelrot_groups(body, *scale, o.appelrot, hs, [&](std::size_t done) {
    if (interrupt_requested.load()) return false;
    progress.update(static_cast<std::int64_t>(done), 0);
    return true;
  });
  progress.finish();
  return groups;
}

/// Every branch sampled (without --l), with a progress line per branch on stderr
/// (cli/sweep_progress.hpp; issue 50, item 8); a signal stops after the current branch.
EquilibriumSet sampled_branches(const EquilibriaOptions& o, const HeavyTopBody& body) {
  std::optional<SweepProgress> progress;
  EquilibriumSet set = equilibrium_branches(body, o.samples, [&](std::size_t done, std::size_t total) {
    if (interrupt_requested.load()) return false;
    if (!progress) progress.emplace(o.quiet, static_cast<std::int64_t>(total), 0, o.subcommand.c_str(), "branches");
    progress->update(static_cast<std::int64_t>(done), 0);
    return true;
  });
  if (progress) progress->finish();
  return set;
}

/// A signal's end: one line, nothing written (the file is written only at the end).
int interrupted(const EquilibriaOptions& o) {
  std::cerr << "lgi: " << o.subcommand << ": interrupted by signal; nothing written\n";
  return interrupted_exit_status();
}

int run_equilibria(const EquilibriaOptions& o) {
  const system::Scene scene = read_scene(o.scene);
  if (scene.suspension) {
    check_flags(o);
    if (!o.appelrot.empty()) throw UsageError("--appelrot: " + scene.file + " is a Cardan top, not a Kovalevskaya top");
    return run_cardan_equilibria(scene, {o.l, o.samples, o.omega_max, o.out, o.command_line, o.subcommand, o.force,
                                         o.quiet});
  }
  if (o.omega_max) throw UsageError("--omega-max: only for a Cardan top (a scene with [suspension])");
  const HeavyTopBody body = equilibria_body(scene);
  check_flags(o);
  if (!o.l) hdf5::check_output_target(o.out, o.force);  // before the work, not after it
  const InterruptGuard interrupt_guard;
  const EquilibriumSet set = o.l ? equilibria_at(body, *o.l) : sampled_branches(o, body);
  if (interrupt_signal() != 0) return interrupted(o);
  std::map<std::string, std::string> parameters = {
      {"subcommand", "equilibria"}, {"command_line", o.command_line}, {"scene_file", scene.file},
      {"scene_toml", scene.toml_text}, {"lgi_version", build_info::version}, {"compiler", build_info::compiler},
      {"cxx_flags", build_info::cxx_flags}};
  if (o.l) parameters["l"] = format_general(*o.l, 17);
  parameters["branches"] = branch_listing(set.branches);
  parameters["branch_labels"] = branch_label_listing(set.branches);
  if (!o.appelrot.empty()) {
    std::string ls;
    for (const double l : o.appelrot) ls += (ls.empty() ? "" : ",") + format_general(l, 17);
    parameters["appelrot_l"] = ls;
  }
  const std::vector<TableGroup> curves = appelrot(o, scene, body);
  if (interrupt_signal() != 0) return interrupted(o);
  write_table_file(o.out, o.force, "equilibria", equilibria_columns(set.rows), parameters, curves);
  if (o.quiet) return exit_ok;
  for (const auto& e : set.rows)
    if (o.l || e.fold || e.class_change) print_row(e);
  if (!o.l)
    std::cout << set.rows.size() << " points on " << set.branches.size() << " branches; wrote " << o.out << '\n';
  return exit_ok;
}

/// The flags both commands end with (--out, --force, --quiet), and the command.
Subcommand with_output(CLI::App* sub, const std::shared_ptr<EquilibriaOptions>& o, const CommandContext& context) {
  sub->add_option("--out", o->out, "Output file (HDF5); the same table as CSV beside it")->required();
  add_force_quiet_flags(*sub, *o, "Replace existing output files");
  return {sub,
          [o, context] {
            o->command_line = context.command_line;
            return run_equilibria(*o);
          },
          [o] { check_flags(*o); }};
}

}  // namespace

Subcommand add_equilibria_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<EquilibriaOptions>();
  auto* sub = app.add_subcommand(
      "equilibria",
      "Relative equilibria (permanent rotations) of a heavy top and their stability: at one momentum l (--l), or "
      "every branch sampled with its folds (experiments/EQUILIBRIA.md)");
  sub->add_option("--scene", o->scene, "Scene file (TOML): a heavy top, a free body, or a Cardan top with a "
                                       "vertical outer axis (docs/cardan.md)")->required();
  sub->add_option("--omega-max", o->omega_max, "Cardan top without --l: omega in [-W, W]");
  sub->add_option("--l", o->l, "The momentum l = Pi.Gamma: every equilibrium there, polished to round-off");
  sub->add_option("--samples", o->samples, "Points per branch without --l")->capture_default_str();
  return with_output(sub, o, context);
}

Subcommand add_bifurcation_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<EquilibriaOptions>();
  auto* sub = app.add_subcommand(
      "bifurcation",
      "The (l, h) bifurcation diagram of a heavy top: every branch of relative equilibria sampled, with its "
      "stability and folds (the table of lgi equilibria without --l; figure: scripts/plots/bifurcation.py)");
  o->subcommand = "bifurcation";
  sub->add_option("--scene", o->scene, "Scene file (TOML): a heavy top, a free body, or a Cardan top with a "
                                       "vertical outer axis")->required();
  sub->add_option("--samples", o->samples, "Points per branch (Cardan top: values of omega)")->capture_default_str();
  sub->add_option("--omega-max", o->omega_max,
                  "Cardan top: the diagram for omega in [-W, W] (default: 3 sqrt(max|grad V| / min M11))");
  sub->add_option("--appelrot", o->appelrot,
                  "Kovalevskaya top: the (h, k) diagram at these l (comma-separated): Appelrot curves, the "
                  "equilibria's (h, k) and the range of k (groups /appelrot*)")
      ->delimiter(',');
  sub->add_option("--appelrot-h", o->appelrot_h, "With --appelrot: the energies a:b:n where the range of k is found "
                                                 "(default: h/(J3 c) from -1.1 to 5, 123 values)");
  return with_output(sub, o, context);
}

}  // namespace lgi::experiments

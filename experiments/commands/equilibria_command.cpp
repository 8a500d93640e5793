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

#include "experiments/analysis/relative_equilibria.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/run_options.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/table_file.hpp"
#include "lgi/build_info.hpp"

namespace lgi::experiments {
namespace {

struct EquilibriaOptions {
  std::string scene, out;
  std::optional<double> l;
  int samples = 400;
  bool force = false, quiet = false;
  std::string command_line;
};

HeavyTopBody heavy_top(const system::Scene& scene) {
  const bool gravity = scene.declared<system::GravityTerm>().has_value();
  if (!scene.is_free_body() && !scene.declares_only<system::GravityTerm>())
    throw InputError(scene.file + ": lgi equilibria needs a heavy top (gravity and no other torque term)");
  HeavyTopBody body;
  body.J = scene.inertia;
  if (gravity)
    body.weight = *scene.mass * scene.declared<system::GravityTerm>()->g * scene.center_of_mass.value_or(Vec3::Zero());
  return body;
}

std::vector<TableColumn> columns_of(const std::vector<RelativeEquilibrium>& rows) {
  std::vector<TableColumn> c = {{"omega"},  {"gamma", 3}, {"angular_momentum", 3}, {"l"},
                                {"h"},      {"branch", 1, true}, {"g1"}, {"g2"},
                                {"stability", 1, true}, {"nonlinearly_stable", 1, true}, {"fold", 1, true},
                                {"residual"}};
  for (const auto& e : rows) {
    c[0].real.push_back(e.omega);
    c[1].real.insert(c[1].real.end(), e.gamma.data(), e.gamma.data() + 3);
    c[2].real.insert(c[2].real.end(), e.angular_momentum.data(), e.angular_momentum.data() + 3);
    c[3].real.push_back(e.l);
    c[4].real.push_back(e.h);
    c[5].whole.push_back(e.branch);
    c[6].real.push_back(e.g1);
    c[7].real.push_back(e.g2);
    c[8].whole.push_back(static_cast<std::int64_t>(e.stability));
    c[9].whole.push_back(e.nonlinearly_stable ? 1 : 0);
    c[10].whole.push_back(e.fold ? 1 : 0);
    c[11].real.push_back(e.residual);
  }
  return c;
}

void print_row(const RelativeEquilibrium& e) {
  std::printf("branch=%d omega=%.17g gamma=(%.17g, %.17g, %.17g) l=%.17g h=%.17g stability=%s g1=%.6e g2=%.6e "
              "nonlinearly_stable=%s%s\n",
              e.branch, e.omega, e.gamma.x(), e.gamma.y(), e.gamma.z(), e.l, e.h, stability_name(e.stability), e.g1,
              e.g2, e.nonlinearly_stable ? "yes" : "no", e.fold ? " fold" : "");
}

int run_equilibria(const EquilibriaOptions& o) {
  const system::Scene scene = read_scene(o.scene);
  const HeavyTopBody body = heavy_top(scene);
  if (o.l && !std::isfinite(*o.l)) throw UsageError("--l: must be a finite number");
  if (o.samples < 3) throw UsageError("--samples: must be at least 3");
  const EquilibriumSet set = o.l ? equilibria_at(body, *o.l) : equilibrium_branches(body, o.samples);
  std::map<std::string, std::string> parameters = {
      {"subcommand", "equilibria"}, {"command_line", o.command_line}, {"scene_file", scene.file},
      {"scene_toml", scene.toml_text}, {"lgi_version", build_info::version}, {"compiler", build_info::compiler},
      {"cxx_flags", build_info::cxx_flags}};
  if (o.l) parameters["l"] = format_general(*o.l, 17);
  std::string branches;
  for (const auto& b : set.branches) branches += std::to_string(b.id) + ": " + b.kind + "\n";
  parameters["branches"] = branches;
  write_table_file(o.out, o.force, "equilibria", columns_of(set.rows), parameters);
  if (o.quiet) return exit_ok;
  for (const auto& e : set.rows)
    if (o.l || e.fold) print_row(e);
  if (!o.l)
    std::cout << set.rows.size() << " points on " << set.branches.size() << " branches; wrote " << o.out << '\n';
  return exit_ok;
}

}  // namespace

Subcommand add_equilibria_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<EquilibriaOptions>();
  auto* sub = app.add_subcommand(
      "equilibria",
      "Relative equilibria (permanent rotations) of a heavy top and their stability: at one momentum l (--l), or "
      "every branch sampled with its folds (experiments/EQUILIBRIA.md)");
  sub->add_option("--scene", o->scene, "Scene file (TOML): a heavy top, or a free body")->required();
  sub->add_option("--l", o->l, "The momentum l = Pi.Gamma: every equilibrium there, polished to round-off");
  sub->add_option("--samples", o->samples, "Points per branch without --l")->capture_default_str();
  sub->add_option("--out", o->out, "Output file (HDF5); the same table as CSV beside it")->required();
  add_force_quiet_flags(*sub, *o, "Replace existing output files");
  return {sub, [o, context] {
            o->command_line = context.command_line;
            return run_equilibria(*o);
          }};
}

Subcommand add_bifurcation_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<EquilibriaOptions>();
  auto* sub = app.add_subcommand(
      "bifurcation",
      "The (l, h) bifurcation diagram of a heavy top: every branch of relative equilibria sampled, with its "
      "stability and folds (the table of lgi equilibria without --l; figure: scripts/plots/bifurcation.py)");
  sub->add_option("--scene", o->scene, "Scene file (TOML): a heavy top, or a free body")->required();
  sub->add_option("--samples", o->samples, "Points per branch")->capture_default_str();
  sub->add_option("--out", o->out, "Output file (HDF5); the same table as CSV beside it")->required();
  add_force_quiet_flags(*sub, *o, "Replace existing output files");
  return {sub, [o, context] {
            o->command_line = context.command_line;
            return run_equilibria(*o);
          }};
}

}  // namespace lgi::experiments

#pragma once
// The options every one-scene, one-scheme command shares (simulate,
// long-time): --scene, --scheme, --dt, --tol, --t-end, declared once with one
// wording (docs: experiments/OUTPUT.md and `lgi <command> --help`).
#include <CLI/CLI.hpp>

namespace lgi::experiments {

/// Options holds scene, scheme (strings) and dt, tol, t_end (std::optional<double>).
template <class Options>
void add_scene_scheme_options(CLI::App& sub, Options& o) {
  sub.add_option("--scene", o.scene, "Scene file (TOML)")->required();
  sub.add_option("--scheme", o.scheme, "Scheme name (see `lgi schemes`)")->required();
  sub.add_option("--dt", o.dt,
                 "Step size (fixed-step schemes; first trial step of adaptive ones). Default: the scene's [run] dt");
  sub.add_option("--tol", o.tol, "Tolerance (adaptive schemes). Default: the scene's [run] tol");
  sub.add_option("--t-end", o.t_end, "Final time. Default: the scene's [run] t_end (needed if it has none)");
}

/// --force and --quiet, with the wording for one output file or a table and its CSV.
template <class Options>
void add_force_quiet_flags(CLI::App& sub, Options& o, const char* force_help) {
  sub.add_flag("--force", o.force, force_help);
  sub.add_flag("--quiet", o.quiet, "Print nothing but errors");
}

}  // namespace lgi::experiments

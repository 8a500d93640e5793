// lgi quantum --scene FILE --hbar H [--m M] [--jmax J] [--levels N] [--jmax-step D] [--tol T]
//   [--ebk] [--statistics] --out FILE.h5 [--force] [--quiet]
// The lowest levels of the quantum top Ĥ = Σ L̂ᵢ²/(2Jᵢ) + c·Γ̂ at vertical
// angular momentum mħ (experiments/QUANTUM.md, docs/quantum.md), each with
// its quantum numbers, its class and its convergence in jmax
// (analysis/quantum/quantum_spectrum.hpp): /spectrum/<column> and a CSV.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "experiments/analysis/quantum/ebk_kovalevskaya.hpp"
#include "experiments/analysis/quantum/lowest_levels.hpp"  // SolveInterrupted
#include "experiments/analysis/quantum/quantum_spectrum.hpp"
#include "experiments/commands/all_commands.hpp"
#include "experiments/commands/quantum_outputs.hpp"
#include "experiments/cli/interrupt_guard.hpp"
#include "experiments/cli/run_options.hpp"
#include "experiments/cli/sweep_progress.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/errors/input_error.hpp"
#include "experiments/io/h5md_writer.hpp"  // OutputFileError
#include "experiments/io/hdf5_support.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/table_file.hpp"
#include "experiments/io/trajectory_observer.hpp"  // interrupt_requested
#include "lgi/build_info.hpp"

namespace lgi::experiments {
namespace {

struct QuantumOptions {
  std::string scene, out;
  double hbar = 0.0;
  int m = 0, jmax = 40, levels = 20, jmax_step = 4;
  double tol = 1e-8;
  bool ebk = false, statistics = false;
  std::string energy_window;  // "LO:HI" (empty: every level)
  double energy_low = -std::numeric_limits<double>::infinity(), energy_high = std::numeric_limits<double>::infinity();
  bool force = false, quiet = false;
  std::string command_line;
};


/// --energy-window LO:HI: two finite numbers, LO < HI; only with --statistics.
void parse_window(QuantumOptions& o) {
  if (o.energy_window.empty()) return;
  if (!o.statistics) throw UsageError("--energy-window: needs --statistics (it selects the levels of /statistics)");
  const auto colon = o.energy_window.find(':');
  const auto bad = [&] { return UsageError("--energy-window: expected LO:HI with LO < HI, got '" + o.energy_window + "'"); };
  if (colon == std::string::npos) throw bad();
  try {
    std::size_t a = 0, b = 0;
    const std::string lo = o.energy_window.substr(0, colon), hi = o.energy_window.substr(colon + 1);
    o.energy_low = std::stod(lo, &a), o.energy_high = std::stod(hi, &b);
    if (a != lo.size() || b != hi.size()) throw bad();
  } catch (const std::logic_error&) {
    throw bad();
  }
  if (!std::isfinite(o.energy_low) || !std::isfinite(o.energy_high) || !(o.energy_low < o.energy_high)) throw bad();
}

void check_flags(QuantumOptions& o) {
  if (!(o.hbar > 0.0) || !std::isfinite(o.hbar)) throw UsageError("--hbar: must be a positive number");
  if (o.jmax > 400) throw UsageError("--jmax: at most 400 (the basis has (jmax+1)^2 - m^2 states)");
  if (o.m < -o.jmax || o.m > o.jmax) throw UsageError("--jmax: must be at least |m| (j runs from |m| to jmax)");
  if (o.levels < 1) throw UsageError("--levels: must be at least 1");
  if (o.jmax_step < 1 || o.jmax_step > 100) throw UsageError("--jmax-step: must be in 1..100");
  if (!(o.tol > 0.0) || !std::isfinite(o.tol)) throw UsageError("--tol: must be a positive number");
  parse_window(o);
}

std::vector<TableColumn> columns_of(const quantum::QuantumSpectrum& q, int m) {
  std::vector<TableColumn> c = {{"index", 1, true}, {"energy"}, {"j", 1, true}, {"m", 1, true}, {"k", 1, true},
                                {"parity", 1, true}, {"converged", 1, true}, {"change_with_jmax"},
                                {"k_conserved", 1, true}};
  for (std::size_t i = 0; i < q.levels.size(); ++i) {
    const quantum::QuantumLevel& l = q.levels[i];
    c[0].whole.push_back(static_cast<std::int64_t>(i));
    c[1].real.push_back(l.energy);
    c[2].whole.push_back(l.j);
    c[3].whole.push_back(m);
    c[4].whole.push_back(l.k);
    c[5].whole.push_back(l.parity);
    c[6].whole.push_back(l.converged ? 1 : 0);
    c[7].real.push_back(l.change_with_jmax);
    c[8].whole.push_back(l.k_conserved ? 1 : 0);
  }
  return c;
}

void print_rows(const quantum::QuantumSpectrum& q) {
  const std::size_t shown = std::min<std::size_t>(q.levels.size(), 20);
  std::printf("%6s %22s %4s %5s %6s %9s %12s\n", "index", "energy", "j", "k", "parity", "converged", "change");
  for (std::size_t i = 0; i < shown; ++i) {
    const quantum::QuantumLevel& l = q.levels[i];
    std::printf("%6zu %22.15g %4d %5d %6d %9s %12.3g\n", i, l.energy, l.j, l.k, l.parity,
                l.converged ? "yes" : "NO", l.change_with_jmax);
  }
  if (shown < q.levels.size()) std::printf("... %zu more levels in the file\n", q.levels.size() - shown);
}

/// One line per /ebk or /statistics summary.
void print_extra(const std::vector<TableGroup>& extra) {
  for (const TableGroup& g : extra) {
    if (g.name == "ebk") {
      double worst = 0.0;
      std::size_t with = 0;
      for (double d : g.columns[5].real)
        if (std::isfinite(d)) worst = std::max(worst, std::abs(d)), ++with;
      std::printf("EBK: max |E_ebk - E_exact| = %.3g over %zu levels (%zu without an EBK level)\n", worst, with,
                  g.columns[5].real.size() - with);
    } else if (g.name == "statistics") {
      const auto& levels = g.columns[2].whole;
      for (std::size_t i = 0; i < levels.size() && i < 20; ++i)
        std::printf("statistics: j %3lld parity %2lld: %4lld levels, Brody beta = %.3f +- %.3f\n",
                    static_cast<long long>(g.columns[0].whole[i]), static_cast<long long>(g.columns[1].whole[i]),
                    static_cast<long long>(levels[i]), g.columns[3].real[i], g.columns[4].real[i]);
    }
  }
}

std::string vector_text(const Eigen::Vector3d& v) {
  return "[" + format_exact(v(0)) + ", " + format_exact(v(1)) + ", " + format_exact(v(2)) + "]";
}

std::map<std::string, std::string> parameters_of(const QuantumOptions& o, const system::Scene& scene,
                                                 const quantum::QuantumSpectrum& q, double wall) {
  const Eigen::Matrix3d& f = q.top.frame;
  return {{"subcommand", "quantum"}, {"command_line", o.command_line}, {"scene_file", scene.file},
          {"scene_toml", scene.toml_text}, {"lgi_version", build_info::version}, {"compiler", build_info::compiler},
          {"cxx_flags", build_info::cxx_flags}, {"hbar", format_exact(o.hbar)}, {"m", std::to_string(o.m)},
          {"jmax", std::to_string(o.jmax)}, {"jmax_step", std::to_string(o.jmax_step)},
          {"levels", std::to_string(o.levels)}, {"tol", format_exact(o.tol)},
          {"converged_rule", "|change_with_jmax| <= tol * max(|energy|, energy_unit), change_with_jmax = "
                             "E(jmax + jmax_step) - E(jmax) for the same level (same block, same rank)"},
          {"energy_unit", format_exact(q.energy_unit)},
          {"hamiltonian", "sum_i L_i^2/(2 J_i) + c.Gamma in the Wigner basis |j,k,m>, j = |m|..jmax (docs/quantum.md)"},
          {"potential", q.top.potential}, {"moments", vector_text(q.top.moments)},
          {"weight", vector_text(q.top.weight)},
          {"frame", "columns: " + vector_text(f.col(0)) + " " + vector_text(f.col(1)) + " " + vector_text(f.col(2))},
          {"symmetry", quantum::symmetry_name(q.top.symmetry)}, {"parity_classes", q.parity_classes},
          {"representation", q.top.is_real() ? "real symmetric" : "complex hermitian"},
          {"dimension", std::to_string(q.dimension)}, {"dimension_check", std::to_string(q.dimension_check)},
          {"method", q.method}, {"wall_seconds", format_general(wall, 6)}};
}

struct Solved {
  quantum::QuantumSpectrum q;
  std::vector<TableGroup> extra;  // /ebk, /statistics, /weyl
  std::vector<std::string> notes;
};

/// The spectrum and the --ebk / --statistics groups; false once a signal came: the solves
/// the EBK tori and the --statistics unfolding and Weyl counts read interrupt_requested and end with
/// SolveInterrupted (quantum_spectrum.hpp).
bool solve(const QuantumOptions& o, const system::Scene& scene, const quantum::QuantumTop& top, bool kovalevskaya,
           Solved& out) {
  quantum::QuantumSettings s;
  s.hbar = o.hbar, s.m = o.m, s.jmax = o.jmax, s.levels = o.levels, s.jmax_step = o.jmax_step, s.tol = o.tol;
  s.stop = &interrupt_requested;
  // Progress on stderr (cli/sweep_progress.hpp; issue 50, item 8): the eigenvalue solves of a heavy
  // top's blocks (a free body's blocks are exact and fast: no line).
  std::optional<SweepProgress> progress;
  s.solved = [&](int done, int total) {
    if (!progress) progress.emplace(o.quiet, total, 0, "quantum", "eigenvalue solves");
    progress->update(done, 0);
  };
  try {
    try {
      out.q = quantum::quantum_spectrum(top, s);
    } catch (const quantum::SolveInterrupted&) {
      throw;
    } catch (const std::runtime_error& e) {
      throw RunError(e.what());
    }
    if (progress) progress->finish();
    progress.reset();
    if (o.ebk)
      out.extra.push_back(
          ebk_group(out.q, o.hbar, o.m, kovalevskaya ? &scene : nullptr, &out.notes, &interrupt_requested));
    if (o.statistics)
      out.extra.push_back(statistics_group(out.q, o.hbar, o.m, o.energy_low, o.energy_high, &interrupt_requested));
    if (o.statistics) out.extra.push_back(weyl_group(out.q, o.hbar, o.m, &interrupt_requested));
  } catch (const quantum::SolveInterrupted&) {
    if (progress) progress->finish();
    return false;
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string(e.what()) + " (scene " + scene.file + ")");
  }
  return interrupt_signal() == 0;
}

int run_quantum(QuantumOptions o) {
  check_flags(o);
  const system::Scene scene = read_scene(o.scene);
  const quantum::QuantumTop top = quantum::quantum_top_of(scene);
  const bool kovalevskaya = quantum::is_kovalevskaya_scene(scene);
  if (o.ebk && !top.is_free() && top.symmetry != quantum::TopSymmetry::symmetric_heavy && !kovalevskaya)
    throw InputError("--ebk: needs a free body, a Lagrange top (J1 = J2, centre of mass on the symmetry axis) or a "
                     "Kovalevskaya top; scene " + scene.file +
                     " is " + quantum::symmetry_name(top.symmetry));
  if (!o.force && hdf5::path_exists(o.out)) throw OutputFileError("output file '" + o.out + "' exists (--force replaces it)");
  hdf5::check_output_target(o.out, o.force);  // a FIFO or a device at --out: before the work, not after it
  const InterruptGuard interrupt_guard;  // Ctrl-C / SIGTERM: solve() reads the flag; nothing is written
  const auto start = std::chrono::steady_clock::now();
  Solved solved;
  if (!solve(o, scene, top, kovalevskaya, solved)) {
    std::cerr << "lgi: quantum: interrupted by signal; nothing written\n";
    return interrupted_exit_status();
  }
  const quantum::QuantumSpectrum& q = solved.q;
  const std::vector<TableGroup>& extra = solved.extra;
  const std::vector<std::string>& notes = solved.notes;
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_table_file(o.out, o.force, "spectrum", columns_of(q, o.m), parameters_of(o, scene, q, wall), extra);
  std::size_t unconverged = 0;
  for (const auto& l : q.levels) unconverged += l.converged ? 0 : 1;
  if (unconverged > 0)
    std::cerr << "lgi: note: " << unconverged << " of " << q.levels.size() << " levels moved by more than tol between "
              << "jmax = " << o.jmax << " and " << o.jmax + o.jmax_step << ": converged = 0 (raise --jmax)\n";
  if (o.quiet) return exit_ok;
  print_rows(q);
  for (const std::string& note : notes) std::cout << note << '\n';
  print_extra(extra);
  std::cout << q.levels.size() << " levels at m = " << o.m << ", hbar = " << format_general(o.hbar, 10)
            << " (" << quantum::symmetry_name(top.symmetry) << "); basis " << q.dimension << " states; "
            << format_general(wall, 3) << " s; wrote " << o.out << '\n';
  return exit_ok;
}

}  // namespace

Subcommand add_quantum_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<QuantumOptions>();
  auto* sub = app.add_subcommand(
      "quantum", "The lowest levels of the quantum top at vertical angular momentum m hbar, each with its quantum "
                 "numbers and its convergence in jmax (experiments/QUANTUM.md)");
  sub->add_option("--scene", o->scene, "Scene file (an SO(3) scene: gravity and a vertical magnetic field)")->required();
  sub->add_option("--hbar", o->hbar, "Planck's constant in the scene's units")->required();
  sub->add_option("--m", o->m, "Vertical angular momentum quantum number (l = m hbar)")->capture_default_str();
  sub->add_option("--jmax", o->jmax, "The basis holds j = |m|..jmax")->capture_default_str();
  sub->add_option("--levels", o->levels, "How many of the lowest levels (a heavy top; a free body writes every "
                                         "level of every j <= jmax)")->capture_default_str();
  sub->add_option("--jmax-step", o->jmax_step, "The convergence check solves again at jmax + this")
      ->capture_default_str();
  sub->add_option("--tol", o->tol, "converged = 1 where |E(jmax + step) - E(jmax)| <= tol * max(|E|, hbar^2/(2 "
                                   "J_min))")->capture_default_str();
  sub->add_option("--out", o->out, "Output file (HDF5); the same table as CSV beside it")->required();
  sub->add_flag("--ebk", o->ebk, "Also write /ebk: EBK levels beside the exact ones, of a Lagrange top or a "
                                 "free body (docs/quantum.md sections 7, 9)");
  sub->add_option("--energy-window", o->energy_window, "With --statistics: only the levels with LO <= E <= HI "
                                                      "enter /statistics (LO:HI)");
  sub->add_flag("--statistics", o->statistics, "Also write /statistics: spacings, Brody beta, number variance and "
                                               "rigidity per symmetry class, unfolded with Weyl's law");
  add_force_quiet_flags(*sub, *o, "Replace existing output files");
  return {sub,
          [o, context] {
            o->command_line = context.command_line;
            return run_quantum(*o);
          },
          [o] { check_flags(*o); }};
}

}  // namespace lgi::experiments

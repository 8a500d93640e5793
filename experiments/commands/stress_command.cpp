// lgi stress: the suite of stiff and extreme cases (experiments/STRESS.md),
// each run against every registered scheme (or those of --schemes), with an
// outcome, an error against a reference, the largest invariant error, the
// work, and a pass flag computed from the case's written criterion.
//
// The pieces: stress_suite (the variants), stress_runner (reference, run,
// error, pass), stress_report (columns, attributes, tallies). Rows go
// through ResultsFile (results_file.hpp) to /results of <out>.partial and
// <out>.csv.partial as they are made (a killed run leaves them readable);
// both are renamed on success (RESULTS.md, "stress"). Each variant's set-up,
// reference and criterion go to the attributes of a group /case_NN.
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "experiments/commands/all_commands.hpp"
#include "experiments/cli/interrupt_guard.hpp"
#include "experiments/cli/scheme_lookup.hpp"
#include "experiments/cli/write_failures.hpp"
#include "experiments/commands/stress/stress_report.hpp"
#include "experiments/commands/stress/stress_runner.hpp"
#include "experiments/commands/stress/stress_suite.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/results_file.hpp"
#include "experiments/io/scenes_location.hpp"
#include "experiments/io/trajectory_observer.hpp"  // interrupt_requested
#include "integrators/registry/registry.hpp"

namespace lgi::experiments {
namespace {
// This file's own namespace: its `using namespace` below does not reach the next
// file of a unity batch (experiments/CMakeLists.txt).
namespace stress_cli {

using integrators::SchemeInfo;
using namespace stress;

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

/// Runs every scheme on every variant, writing each row as it is made;
/// returns the rows and, if a signal stopped the suite, why.
std::vector<Row> run_suite(std::vector<Variant>& variants, const std::vector<const SchemeInfo*>& schemes,
                           double budget, bool progress, ResultsFile& file, std::string& stopped) {
  std::vector<Row> rows;
  std::size_t k = 0;
  // Every run reads the flag as RunConfig::stop and ends after its current
  // step; the run it cut short is not a result, so the suite stops before
  // writing it (the rows before it are in the file).
  auto interrupted = [&stopped] {
    if (!interrupt_requested.load(std::memory_order_relaxed)) return false;
    stopped = integrators::interrupted_status;
    return true;
  };
  for (Variant& v : variants) {
    ++k;
    if (progress)
      std::cerr << "\r\033[K[" << k << "/" << variants.size() << "] " << v.case_id << ": " << v.variant
                << std::flush;
    compute_reference(v, budget);
    if (interrupted()) break;
    char group[32];
    std::snprintf(group, sizeof group, "case_%02zu", k - 1);
    file.write_group(group, case_attributes(v));
    for (const SchemeInfo* s : schemes) {
      Row row = run_row(v, *s, budget);
      if (interrupted()) break;
      append_row(file, row, v);
      rows.push_back(std::move(row));
    }
    if (!stopped.empty()) break;
  }
  if (progress) std::cerr << "\r\033[K" << std::flush;
  return rows;
}

void write_parameters(ResultsFile& file, const StressOptions& o, const std::vector<const SchemeInfo*>& schemes,
                      double budget, std::size_t variants) {
  std::string scheme_list;
  for (const auto* s : schemes) scheme_list += (scheme_list.empty() ? "" : ",") + s->name;
  ResultAttributes p;
  p.text["command_line"] = o.command_line;
  p.text["subcommand"] = "stress";
  p.text["schemes"] = scheme_list;
  p.text["criteria"] = "experiments/STRESS.md";
  p.number["budget_seconds"] = budget;
  p.integer["quick"] = o.quick ? 1 : 0;
  p.integer["variants"] = static_cast<std::int64_t>(variants);
  file.write_parameters(p);
}

double checked_budget(const StressOptions& o) {
  const double budget = o.budget.value_or(o.quick ? 2.0 : 10.0);
  if (!(budget > 0.0) || !std::isfinite(budget)) throw UsageError("--budget: must be a finite number > 0");
  return budget;
}

int stress_command(const StressOptions& o) {
  const std::vector<const SchemeInfo*> schemes = selected_schemes(o.schemes);
  const double budget = checked_budget(o);

  std::vector<Variant> variants = build_suite({o.quick, shipped_scenes_dir(o.scenes_dir)});
  for (auto& v : variants) v.criterion.text = criterion_text(v.criterion);
  // Signals only set the flag from before the first file exists until the results are published (interrupt_guard.hpp).
  const InterruptGuard interrupt_guard;
  ResultsFile file(o.out, o.force, result_columns());
  write_parameters(file, o, schemes, budget, variants.size());

  std::string stopped;
  const double cpu_start = integrators::detail::cpu_now();
  const std::vector<Row> rows = run_suite(variants, schemes, budget, !o.quiet && ::isatty(2), file, stopped);
  const double cpu_total = integrators::detail::cpu_now() - cpu_start;

  const Summary summary = summarise(rows);
  const ResultAttributes diag = summary_attributes(summary, stopped.empty() ? "ok" : stopped, cpu_total, rows.size());
  if (!stopped.empty()) {
    file.abandon(diag);
    std::cerr << "lgi: stress " << stopped << " after " << rows.size() << " rows; partial results kept in "
              << file.partial_path() << " and " << file.csv_partial_path() << '\n';
    return interrupted_exit_status();
  }
  file.finish(diag);

  if (!o.quiet) {
    std::ostringstream s;
    s << summary_table(summary);
    s << "cpu_seconds=" << fmt(cpu_total, 4) << " schemes=" << schemes.size() << " variants=" << variants.size()
      << " rows=" << rows.size() << " out=" << file.path() << " csv=" << file.csv_path() << '\n';
    for (const auto& c : summary.order) {
      const Tally& t = summary.by_case.at(c);
      if (t.not_passed.empty()) continue;
      s << "not passed in " << c << ":";
      for (const auto& [scheme, n] : t.not_passed) s << ' ' << scheme << '(' << n << ')';
      s << '\n';
    }
    std::cout << s.str() << std::flush;
  }
  return exit_ok;
}

}  // namespace stress_cli
}  // namespace

Subcommand add_stress_subcommand(CLI::App& app, const CommandContext& context) {
  using namespace stress_cli;
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
  sub->footer(exit_status_help);
  return {sub,
          [o, context] {
            o->command_line = context.command_line;
            return run_with_write_failures_as_run_errors([&] { return stress_command(*o); });
          },
          [o] {
            (void)selected_schemes(o->schemes);
            (void)checked_budget(*o);
          }};
}

}  // namespace lgi::experiments

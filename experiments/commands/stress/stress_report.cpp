#include "experiments/commands/stress/stress_report.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace lgi::experiments::stress {
namespace {

/// An ok row whose answer is wrong beyond doubt: error > 1, or a non-finite error or invariant error.
bool silently_wrong(const Row& r) {
  if (r.outcome != Outcome::ok) return false;
  if (!r.state_judged) return !std::isfinite(r.error) || !(r.max_invariant_error <= 1.0);
  return !(r.error <= 1.0) || !std::isfinite(r.max_invariant_error);
}

}  // namespace

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

Summary summarise(const std::vector<Row>& rows) {
  Summary s;
  for (const Row& r : rows) {
    if (!s.by_case.count(r.case_id)) s.order.push_back(r.case_id);
    for (Tally* t : {&s.by_case[r.case_id], &s.total}) {
      ++t->runs;
      t->ok += r.outcome == Outcome::ok;
      t->refused += r.outcome == Outcome::refused;
      t->failed += r.outcome == Outcome::failed;
      t->pass += r.pass;
      t->wrong += silently_wrong(r) ? 1 : 0;
      if (!r.pass) ++t->not_passed[r.scheme];
    }
  }
  return s;
}

ResultAttributes summary_attributes(const Summary& s, const std::string& status, double cpu_seconds,
                                    std::size_t rows) {
  ResultAttributes diag;
  diag.text["status"] = status;
  diag.number["cpu_seconds"] = cpu_seconds;
  diag.integer["rows"] = static_cast<std::int64_t>(rows);
  diag.integer["passes"] = s.total.pass;
  diag.integer["ok"] = s.total.ok;
  diag.integer["refused"] = s.total.refused;
  diag.integer["failed"] = s.total.failed;
  diag.integer["silently_wrong"] = s.total.wrong;
  return diag;
}

std::string summary_table(const Summary& s) {
  std::ostringstream out;
  auto line = [&](const std::string& name, const Tally& t) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%-12s %6d %6d %8d %7d %6d %9d %7d", name.c_str(), t.runs, t.ok, t.refused,
                  t.failed, t.pass, t.runs - t.pass, t.wrong);
    out << buf << '\n';
  };
  out << "case           runs     ok  refused  failed   pass  not_pass  wrong\n";
  for (const auto& c : s.order) line(c, s.by_case.at(c));
  line("total", s.total);
  return out.str();
}

}  // namespace lgi::experiments::stress

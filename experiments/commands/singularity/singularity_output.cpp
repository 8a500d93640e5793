#include "experiments/commands/singularity/singularity_output.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "experiments/io/number_format.hpp"
#include "experiments/io/results_file.hpp"

namespace lgi::experiments::singularity {
namespace {

/// /scenes/<key>/runs/<label>: one run's attributes, step history, centre of mass and Euler angles.
void write_run_group(H5& h5, const std::string& p, const RunRecord& r, const StudyScene& sc) {
  const hsize_t G = sc.grid.size();
  const hdf5::Handle rg = h5.group(p);
  const Method& m = r.method;
  h5.text(rg.get(), "method", m.name);
  h5.text(rg.get(), "family", m.baseline ? std::string("baseline") : m.scheme->family);
  h5.text(rg.get(), "coordinates", m.baseline ? bl::coordinates_name(m.id.coordinates) : "SO(3) x R^3");
  h5.text(rg.get(), "stepper", stepper_text(m));
  h5.text(rg.get(), "guard", guard_text(m));
  if (m.adaptive) h5.number(rg.get(), "tol", sc.tol);
  else h5.number(rg.get(), "dt", sc.dt);
  h5.text(rg.get(), "outcome", r.stats.ok ? "ok" : "failed");
  h5.text(rg.get(), "status", r.stats.status);
  h5.number(rg.get(), "t_final", r.stats.t_final);
  h5.integer(rg.get(), "steps", r.stats.steps);
  h5.integer(rg.get(), "rejected_steps", r.stats.work.rejected_steps);
  h5.integer(rg.get(), "rhs_evaluations", r.stats.work.rhs_evaluations);
  h5.number(rg.get(), "cpu_seconds", r.cpu_seconds);
  h5.number(rg.get(), "h_min", r.h_min);
  h5.number(rg.get(), "h_median", r.h_median);
  h5.number(rg.get(), "h_max", r.h_max);
  h5.number(rg.get(), "t_at_h_min", r.t_at_h_min);
  h5.number(rg.get(), "com_max_deviation", r.com_max_deviation);
  h5.integer(rg.get(), "com_points_compared", r.com_points);
  {
    const hdf5::Handle sh = h5.group(p + "/step_history");
    h5.dataset(sh.get(), "time", r.step_end, {r.step_end.size()}, "s");
    h5.dataset(sh.get(), "step_size", r.step_size, {r.step_size.size()}, "s");
  }
  h5.dataset(rg.get(), "center_of_mass", r.com, {G, 3}, "m");
  h5.dataset(rg.get(), "com_deviation", r.com_deviation, {G}, "m");
  if (is_euler(m)) {
    h5.number(rg.get(), "min_abs_sin_theta", r.min_abs_sin_theta);
    const hdf5::Handle eg = h5.group(p + "/euler_zxz");
    const hsize_t n = r.e_time.size();
    h5.dataset(eg.get(), "time", r.e_time, {n}, "s");
    h5.dataset(eg.get(), "psi", r.psi, {n}, "rad");
    h5.dataset(eg.get(), "theta", r.theta, {n}, "rad");
    h5.dataset(eg.get(), "phi", r.phi, {n}, "rad");
    h5.dataset(eg.get(), "theta_dot", r.theta_dot, {n}, "s-1");
  }
}

const char* coordinates_column(const Method& m) {
  return m.baseline ? bl::coordinates_name(m.id.coordinates) : "lie-group";
}

}  // namespace

void write_scene_group(H5& h5, const std::string& key, const StudyScene& sc, const std::vector<double>& reference,
                       const std::vector<RunRecord>& runs) {
  const hsize_t G = sc.grid.size();
  const std::string base = "/scenes/" + key;
  const hdf5::Handle g = h5.group(base);
  h5.text(g.get(), "scene_file", sc.scene->file);
  h5.text(g.get(), "scene_name", sc.scene->name);
  h5.text(g.get(), "scene_toml", sc.scene->toml_text);
  h5.number(g.get(), "t_end", sc.t_end);
  h5.number(g.get(), "tol", sc.tol);
  h5.number(g.get(), "dt", sc.dt);
  h5.numbers(g.get(), "center_of_mass_body", {sc.chi.x(), sc.chi.y(), sc.chi.z()});
  {
    const hdf5::Handle gg = h5.group(base + "/grid");
    h5.dataset(gg.get(), "time", sc.grid, {G}, "s");
  }
  {
    const hdf5::Handle rg = h5.group(base + "/reference");
    h5.text(rg.get(), "scheme", reference_scheme);
    h5.number(rg.get(), "tol", reference_tol);
    h5.dataset(rg.get(), "center_of_mass", reference, {G, 3}, "m");
  }
  const hdf5::Handle all_runs = h5.group(base + "/runs");
  for (const RunRecord& r : runs) write_run_group(h5, base + "/runs/" + r.method.label, r, sc);
}

void write_results_table(H5& h5, const std::vector<SummaryRow>& rows) {
  const hdf5::Handle sg = h5.group("/results");
  std::vector<std::string> scene_col, method_col, coord_col, stepper_col, guard_col, outcome_col, status_col;
  std::vector<double> tol_col, dt_col, t_final, cpu, h_min, h_median, h_max, t_hmin, sin_min, com_dev;
  std::vector<std::int64_t> steps, rejected, rhs, compared;
  for (const auto& row : rows) {
    const RunRecord& r = *row.r;
    const Method& m = r.method;
    scene_col.push_back(row.scene);
    method_col.push_back(m.name);
    coord_col.push_back(coordinates_column(m));
    stepper_col.push_back(stepper_text(m));
    guard_col.push_back(guard_text(m));
    outcome_col.push_back(r.stats.ok ? "ok" : "failed");
    status_col.push_back(r.stats.status);
    tol_col.push_back(m.adaptive ? row.tol : nan);
    dt_col.push_back(m.adaptive ? nan : row.dt);
    t_final.push_back(r.stats.t_final);
    cpu.push_back(r.cpu_seconds);
    h_min.push_back(r.h_min);
    h_median.push_back(r.h_median);
    h_max.push_back(r.h_max);
    t_hmin.push_back(r.t_at_h_min);
    sin_min.push_back(r.min_abs_sin_theta);
    com_dev.push_back(r.com_max_deviation);
    steps.push_back(r.stats.steps);
    rejected.push_back(r.stats.work.rejected_steps);
    rhs.push_back(r.stats.work.rhs_evaluations);
    compared.push_back(r.com_points);
  }
  const hsize_t n = rows.size();
  h5.string_dataset(sg.get(), "scene", scene_col);
  h5.string_dataset(sg.get(), "method", method_col);
  h5.string_dataset(sg.get(), "coordinates", coord_col);
  h5.string_dataset(sg.get(), "stepper", stepper_col);
  h5.string_dataset(sg.get(), "guard", guard_col);
  h5.string_dataset(sg.get(), "outcome", outcome_col);
  h5.string_dataset(sg.get(), "status", status_col);
  h5.dataset(sg.get(), "tol", tol_col, {n});
  h5.dataset(sg.get(), "dt", dt_col, {n}, "s");
  h5.dataset(sg.get(), "t_final", t_final, {n}, "s");
  h5.int_dataset(sg.get(), "steps", steps);
  h5.int_dataset(sg.get(), "rejected_steps", rejected);
  h5.int_dataset(sg.get(), "rhs_evaluations", rhs);
  h5.dataset(sg.get(), "cpu_seconds", cpu, {n}, "s");
  h5.dataset(sg.get(), "h_min", h_min, {n}, "s");
  h5.dataset(sg.get(), "h_median", h_median, {n}, "s");
  h5.dataset(sg.get(), "h_max", h_max, {n}, "s");
  h5.dataset(sg.get(), "t_at_h_min", t_hmin, {n}, "s");
  h5.dataset(sg.get(), "min_abs_sin_theta", sin_min, {n});
  h5.dataset(sg.get(), "com_max_deviation", com_dev, {n}, "m");
  h5.int_dataset(sg.get(), "com_points_compared", compared);
}

void write_results_csv(const std::string& csv, const std::vector<SummaryRow>& rows, bool force) {
  const std::string csv_partial = csv + ".partial";
  std::ofstream f(csv_partial);
  if (!f) throw OutputFileError("cannot write '" + csv_partial + "'");
  f << "scene,method,coordinates,stepper,guard,tol,dt,outcome,status,t_final,steps,rejected_steps,"
       "rhs_evaluations,cpu_seconds,h_min,h_median,h_max,t_at_h_min,min_abs_sin_theta,com_max_deviation,"
       "com_points_compared\n";
  for (const auto& row : rows) {
    const RunRecord& r = *row.r;
    const Method& m = r.method;
    f << row.scene << ',' << hdf5::csv_text(m.name) << ',' << coordinates_column(m) << ',' << stepper_text(m) << ','
      << guard_text(m) << ',' << (m.adaptive ? format_general(row.tol, 3) : "") << ','
      << (m.adaptive ? "" : format_general(row.dt, 3)) << ',' << (r.stats.ok ? "ok" : "failed") << ','
      << hdf5::csv_text(r.stats.status) << ',' << format_general(r.stats.t_final, 10) << ',' << r.stats.steps << ','
      << r.stats.work.rejected_steps << ',' << r.stats.work.rhs_evaluations << ',' << format_general(r.cpu_seconds, 4) << ','
      << format_general(r.h_min, 4) << ',' << format_general(r.h_median, 4) << ',' << format_general(r.h_max, 4) << ','
      << format_general(r.t_at_h_min, 8) << ',' << format_general(r.min_abs_sin_theta, 4) << ',' << format_general(r.com_max_deviation, 4)
      << ',' << r.com_points << '\n';
  }
  f.close();
  if (!f) throw OutputWriteError("cannot write '" + csv_partial + "' (kept)");
  hdf5::publish(csv_partial, csv, force, "the table is");
}

}  // namespace lgi::experiments::singularity

// lgi singularity: the Euler-angle singularity study (experiments/SINGULARITY.md).
//
// Two scenes: heavy_top_trindade_singular (the c.o.m. swings through the
// bottom, θ passing within nanoradians of π at every swing) and
// heavy_top_trindade_4 (the slow top falls toward θ = π). On each: every
// baseline (the euler-zxz ones also with the singularity guard turned off,
// to show what Trindade & Sampaio's integration did), several Lie-group
// schemes, and a tight reference. Per run: outcome, counts, CPU time, the
// accepted step sizes, the centre of mass R χ on a common time grid, and for
// Euler angles the raw ψ, θ, φ, θ̇ at every accepted step.
#include <hdf5.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "experiments/scenes_location.hpp"
#include "experiments/step_settings.hpp"
#include "experiments/commands.hpp"
#include "experiments/exit_status.hpp"
#include "experiments/h5md_writer.hpp"
#include "experiments/hdf5_support.hpp"
#include "experiments/results_file.hpp"
#include "experiments/scene_reader.hpp"
#include "integrators/baselines/baselines.hpp"
#include "integrators/registry.hpp"

namespace lgi::experiments {
namespace {

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

namespace bl = integrators::baselines;
using integrators::Observer;
using integrators::RunConfig;
using integrators::RunStats;
using lie::Mat3;
using lie::Vec3;
using system::State;

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double reference_tol = 1e-12;
constexpr const char* reference_scheme = "rkmk-dp54";
constexpr double grid_spacing = 0.01;

// ---- HDF5 output (C API), errors as OutputFileError ------------------------------

/// The study's file: attributes through the shared writers, plain (not
/// chunked) datasets written once. Errors: "cannot write <what> in '<path>'".
class H5 {
 public:
  explicit H5(const std::string& path)
      : path_(path), fail_([this](const std::string& what) { throw OutputFileError(what + " in '" + path_ + "'"); }) {
    file_ = hdf5::Handle(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
    if (!file_.valid()) throw OutputFileError("cannot create '" + path + "'");
  }
  H5(const H5&) = delete;
  H5& operator=(const H5&) = delete;
  void close() { file_.reset(); }
  hid_t file() const { return file_.get(); }
  const hdf5::Fail& fail() const { return fail_; }

  /// Creates the group `path` (parents must exist).
  hdf5::Handle group(const std::string& path) { return hdf5::create_group(file(), path, fail_); }
  void text(hid_t obj, const char* name, const std::string& value) {
    hdf5::write_vlen_string(obj, name, value, /*ascii=*/false, fail_);
  }
  void number(hid_t obj, const char* name, double value) { hdf5::write_double_attribute(obj, name, value, fail_); }
  void integer(hid_t obj, const char* name, std::int64_t value) {
    hdf5::write_int_attribute(obj, name, H5T_STD_I64LE, value, fail_);
  }
  void numbers(hid_t obj, const char* name, const std::vector<double>& v) {
    hdf5::write_double_array(obj, name, v, fail_);
  }
  /// A float64 dataset of shape dims (row-major data), with an optional unit attribute.
  void dataset(hid_t parent, const char* name, const std::vector<double>& data, const std::vector<hsize_t>& dims,
               const char* unit = nullptr) {
    const hdf5::Handle d =
        write_dataset(parent, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, dims, data.data(), data.size());
    if (unit) text(d.get(), "unit", unit);
  }
  void int_dataset(hid_t parent, const char* name, const std::vector<std::int64_t>& data) {
    write_dataset(parent, name, H5T_STD_I64LE, H5T_NATIVE_INT64, {data.size()}, data.data(), data.size());
  }
  void string_dataset(hid_t parent, const char* name, const std::vector<std::string>& data) {
    std::vector<const char*> p;
    for (const auto& s : data) p.push_back(s.c_str());
    const hdf5::Handle type = hdf5::vlen_string_type(/*ascii=*/false, fail_);
    write_dataset(parent, name, type.get(), type.get(), {data.size()}, p.data(), data.size());
  }
  void flush() { H5Fflush(file(), H5F_SCOPE_GLOBAL); }

 private:
  hdf5::Handle write_dataset(hid_t parent, const char* name, hid_t file_type, hid_t memory_type,
                             const std::vector<hsize_t>& dims, const void* data, std::size_t elements) {
    hsize_t n = 1;
    for (hsize_t d : dims) n *= d;
    if (n != elements) throw OutputFileError("internal: dataset " + std::string(name) + " has the wrong size");
    const hdf5::Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
    hdf5::Handle d(H5Dcreate2(parent, name, file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
    if (!d.valid() || (n && H5Dwrite(d.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0))
      fail_(std::string("cannot write dataset ") + name);
    return d;
  }

  hdf5::QuietHdf5Errors quiet_;  // for the file's lifetime: errors arrive as OutputFileError
  std::string path_;
  hdf5::Fail fail_;
  hdf5::Handle file_;
};

// ---- methods and runs ------------------------------------------------------------

struct Method {
  std::string name;   // as in the tables: a registry name, "+ (unguarded)" for the euler runs without guard
  std::string label;  // HDF5 group name
  bool baseline = false;
  bl::BaselineId id{bl::Coordinates::euler_zxz, bl::Stepper::rk4};
  bool guarded = true;
  const integrators::SchemeInfo* scheme = nullptr;
  bool adaptive = false;
};

std::string label_of(std::string name) {
  for (char& c : name)
    if (c == '/' || c == ' ' || c == '(' || c == ')') c = '_';
  while (!name.empty() && name.back() == '_') name.pop_back();
  std::string out;
  for (char c : name)
    if (!(c == '_' && !out.empty() && out.back() == '_')) out += c;
  return out;
}

struct SceneCase {
  std::string key;   // HDF5 group name
  std::string file;  // path
  double t_end_quick;
};

struct RunRecord {
  Method method;
  RunStats stats;             // of the history run
  double cpu_seconds = 0.0;   // of the timing run (no observer work)
  std::vector<double> step_end, step_size;
  std::vector<double> e_time, psi, theta, phi, theta_dot;  // euler-zxz only
  std::vector<double> com;                                  // [G][3], NaN where not reached
  std::vector<double> com_deviation;                        // [G]
  double com_max_deviation = nan;
  std::int64_t com_points = 0;
  double min_abs_sin_theta = nan;
  double h_min = nan, h_median = nan, h_max = nan, t_at_h_min = nan;
};

/// Records the end time of every accepted step and, for Euler angles, the raw angles and θ̇.
class HistoryObserver final : public Observer {
 public:
  HistoryObserver(RunRecord& r, const Mat3& J_inv, bool euler) : r_(r), J_inv_(J_inv), euler_(euler) {}
  void observe_euler_zxz(const lie::EulerZXZ& a) override { angles_ = a; }
  void observe(std::int64_t, double t, const State& s) override {
    times_.push_back(t);
    if (!euler_) return;
    const Vec3 W = J_inv_ * s.Pi;
    r_.e_time.push_back(t);
    r_.psi.push_back(angles_.psi);
    r_.theta.push_back(angles_.theta);
    r_.phi.push_back(angles_.phi);
    r_.theta_dot.push_back(W.x() * std::cos(angles_.phi) - W.y() * std::sin(angles_.phi));
  }
  const std::vector<double>& times() const { return times_; }

 private:
  RunRecord& r_;
  Mat3 J_inv_;
  bool euler_;
  lie::EulerZXZ angles_{};
  std::vector<double> times_;
};

/// Centre of mass R χ at the grid times (the baselines observe exactly there).
class GridObserver final : public Observer {
 public:
  GridObserver(const std::vector<double>& grid, const Vec3& chi, std::vector<double>& com)
      : grid_(grid), chi_(chi), com_(com) {}
  void observe(std::int64_t, double t, const State& s) override {
    while (next_ < grid_.size() && grid_[next_] < t - 1e-9) ++next_;
    if (next_ >= grid_.size()) return;
    const Vec3 p = s.R * chi_;
    for (int k = 0; k < 3; ++k) com_[3 * next_ + static_cast<std::size_t>(k)] = p[k];
    ++next_;
  }

 private:
  const std::vector<double>& grid_;
  Vec3 chi_;
  std::vector<double>& com_;
  std::size_t next_ = 0;
};

RunStats run_method(const Method& m, const system::AnyModel& model, State& s, const RunConfig& cfg, Observer& obs,
                    const std::vector<double>* grid) {
  if (m.baseline) {
    bl::BaselineOptions o;
    if (!m.guarded) {
      o.euler_singular_threshold = 0.0;
      o.euler_fixed_step_resolution = 0.0;
    }
    o.output_times = grid;
    return bl::run_baseline(m.id.coordinates, m.id.stepper, model, s, cfg, obs, o);
  }
  return m.scheme->run(model, s, cfg, obs);
}

/// R χ on the grid for a registry scheme: one run per grid interval, state carried over.
void grid_run_segmented(const Method& m, const system::AnyModel& model, const State& initial, RunConfig cfg,
                        const std::vector<double>& grid, const Vec3& chi, std::vector<double>& com) {
  State s = initial;
  auto put = [&](std::size_t i) {
    const Vec3 p = s.R * chi;
    for (int k = 0; k < 3; ++k) com[3 * i + static_cast<std::size_t>(k)] = p[k];
  };
  put(0);
  integrators::NullObserver none;
  cfg.save_every = std::int64_t{1} << 62;
  for (std::size_t i = 1; i < grid.size(); ++i) {
    cfg.t0 = grid[i - 1];
    cfg.t_end = grid[i];
    if (!m.scheme->run(model, s, cfg, none).ok) return;
    put(i);
  }
}

void step_statistics(RunRecord& r, const std::vector<double>& times) {
  for (std::size_t i = 1; i < times.size(); ++i) {
    r.step_end.push_back(times[i]);
    r.step_size.push_back(times[i] - times[i - 1]);
  }
  if (r.step_size.empty()) return;
  // Statistics leave out the first step (the starting-step heuristic) and the
  // last (clipped to t_end) when there are more than two.
  std::vector<double> h = r.step_size;
  std::size_t first = 0;
  if (h.size() > 2) {
    h.pop_back();
    h.erase(h.begin());
    first = 1;
  }
  const auto it = std::min_element(h.begin(), h.end());
  r.h_min = *it;
  r.t_at_h_min = r.step_end[first + static_cast<std::size_t>(it - h.begin())];
  r.h_max = *std::max_element(h.begin(), h.end());
  std::nth_element(h.begin(), h.begin() + static_cast<std::ptrdiff_t>(h.size() / 2), h.end());
  r.h_median = h[h.size() / 2];
}

std::string format(double x, int precision = 6) {
  if (std::isnan(x)) return "nan";
  std::ostringstream s;
  s.precision(precision);
  s << x;
  return s.str();
}

std::vector<Method> study_methods(bool quick, const system::AnyModel& model) {
  std::vector<Method> out;
  auto add_baseline = [&](bl::Coordinates c, bl::Stepper s, bool guarded) {
    Method m;
    m.baseline = true;
    m.id = {c, s};
    m.guarded = guarded;
    m.name = bl::baseline_name(c, s) + (guarded ? "" : " (unguarded)");
    m.label = label_of(m.name);
    m.adaptive = bl::stepper_is_adaptive(s);
    out.push_back(m);
  };
  auto add_scheme = [&](const std::string& name) {
    const integrators::SchemeInfo* s = integrators::find_scheme(name);
    if (!s || !integrators::unsupported_reason(*s, model).empty()) return;
    Method m;
    m.name = name;
    m.label = label_of(name);
    m.scheme = s;
    m.adaptive = s->properties.adaptive;
    out.push_back(m);
  };
  using C = bl::Coordinates;
  using S = bl::Stepper;
  if (quick) {
    add_baseline(C::euler_zxz, S::rk4, true);
    add_baseline(C::euler_zxz, S::dopri5, true);
    add_baseline(C::euler_zxz, S::dopri5, false);
    add_baseline(C::rotvec, S::dopri5, true);
    add_baseline(C::quat, S::dopri5, true);
    add_baseline(C::matrix, S::rkf78, true);
    add_baseline(C::quat_normalized, S::rosenbrock4, true);
    add_scheme("rkmk4");
    add_scheme("rkmk-dp54");
    return out;
  }
  for (C c : bl::all_coordinates)
    for (S s : bl::all_steppers) add_baseline(c, s, true);
  for (S s : bl::all_steppers) add_baseline(C::euler_zxz, s, false);
  // Lie-group schemes: the explicit ones always registered, and later ones by name when present.
  for (const char* name : {"rkmk4", "rkmk-dp54", "cg4a", "cf4", "lgvi", "split-exact", "simo-wong", "rkmk-gauss4"})
    add_scheme(name);
  return out;
}

int singularity(const SingularityOptions& o) {
  if (o.out.empty()) throw UsageError("--out: an output file is required");
  if (o.tol && !(*o.tol > 0.0 && std::isfinite(*o.tol))) throw UsageError("--tol: must be a finite number > 0");
  if (o.dt && !(*o.dt > 0.0 && std::isfinite(*o.dt))) throw UsageError("--dt: must be a finite number > 0");
  const std::string csv = results_csv_path(o.out);
  struct stat st {};
  if (!o.force && ::stat(o.out.c_str(), &st) == 0)
    throw OutputFileError("output file '" + o.out + "' exists (use --force to replace it)");
  if (!o.force && ::stat(csv.c_str(), &st) == 0)
    throw OutputFileError("output file '" + csv + "' exists (use --force to replace it)");

  const std::string scenes_dir = shipped_scenes_dir(o.scenes_dir);
  const std::vector<SceneCase> cases = {
      {"trindade_singular", scenes_dir + "/heavy_top_trindade_singular.toml", 2.5},
      {"trindade_4", scenes_dir + "/heavy_top_trindade_4.toml", 4.0},
  };

  const std::string partial = o.out + ".partial";
  H5 h5(partial);
  const std::string utc = hdf5::utc_now_iso8601();
  hdf5::write_h5md_metadata(h5.file(), /*units_module=*/false, h5.fail());
  h5.group("/scenes");

  struct SummaryRow {
    std::string scene;
    const RunRecord* r;
    double tol, dt;
  };
  std::vector<std::vector<RunRecord>> all(cases.size());
  std::vector<SummaryRow> rows;
  double tol_used = 0.0, dt_used = 0.0;

  for (std::size_t ci = 0; ci < cases.size(); ++ci) {
    const SceneCase& sc = cases[ci];
    const system::Scene scene = read_scene(sc.file);
    const system::AnyModel model = system::make_model(scene);
    const double scene_t_end = resolve_t_end(std::nullopt, scene, /*allow_zero=*/false);
    const double t_end = o.quick ? std::min(sc.t_end_quick, scene_t_end) : scene_t_end;
    const double tol = o.tol ? *o.tol : scene.tol.value_or(1e-8);
    const double dt = o.dt ? *o.dt : scene.dt.value_or(1e-3);
    tol_used = tol;
    dt_used = dt;
    const Vec3 chi = scene.center_of_mass.value_or(Vec3::Zero());
    const Mat3 J_inv = system::make_inertia(scene.inertia).J_inv;
    std::vector<double> grid;
    const auto G = static_cast<std::size_t>(std::llround(t_end / grid_spacing)) + 1;
    for (std::size_t i = 0; i < G; ++i) grid.push_back(std::min(t_end, static_cast<double>(i) * grid_spacing));

    // Reference: rkmk-dp54 at a tight tolerance on the grid.
    std::vector<double> ref(3 * G, nan);
    {
      Method m;
      m.scheme = integrators::find_scheme(reference_scheme);
      RunConfig cfg;
      cfg.t_end = t_end;
      cfg.tol = reference_tol;
      grid_run_segmented(m, model, scene.initial, cfg, grid, chi, ref);
    }

    for (const Method& m : study_methods(o.quick, model)) {
      RunRecord r;
      r.method = m;
      RunConfig cfg;
      cfg.t_end = t_end;
      if (m.adaptive) cfg.tol = tol;
      else cfg.dt = dt;
      const bool euler = m.baseline && m.id.coordinates == bl::Coordinates::euler_zxz;
      // Timing: nothing observed in between.
      {
        State s = scene.initial;
        RunConfig c = cfg;
        c.save_every = std::int64_t{1} << 62;
        integrators::NullObserver none;
        r.cpu_seconds = run_method(m, model, s, c, none, nullptr).cpu_seconds;
      }
      // History: every accepted step.
      {
        State s = scene.initial;
        RunConfig c = cfg;
        c.save_every = 1;
        HistoryObserver h(r, J_inv, euler);
        r.stats = run_method(m, model, s, c, h, nullptr);
        step_statistics(r, h.times());
        if (euler) {
          double mn = std::numeric_limits<double>::infinity();
          for (double th : r.theta) mn = std::min(mn, std::abs(std::sin(th)));
          r.min_abs_sin_theta = mn;
        }
      }
      // Centre of mass on the grid.
      r.com.assign(3 * G, nan);
      if (m.baseline) {
        State s = scene.initial;
        GridObserver g(grid, chi, r.com);
        run_method(m, model, s, cfg, g, &grid);
      } else {
        grid_run_segmented(m, model, scene.initial, cfg, grid, chi, r.com);
      }
      r.com_deviation.assign(G, nan);
      double dmax = 0.0;
      for (std::size_t i = 0; i < G; ++i) {
        const Vec3 p(r.com[3 * i], r.com[3 * i + 1], r.com[3 * i + 2]);
        const Vec3 q(ref[3 * i], ref[3 * i + 1], ref[3 * i + 2]);
        if (!p.allFinite() || !q.allFinite()) continue;
        r.com_deviation[i] = (p - q).norm();
        dmax = std::max(dmax, r.com_deviation[i]);
        ++r.com_points;
      }
      if (r.com_points > 0) r.com_max_deviation = dmax;
      if (!o.quiet) {
        std::cout << sc.key << ' ' << m.name << " outcome=" << (r.stats.ok ? "ok" : "failed")
                  << " t_final=" << format(r.stats.t_final) << " steps=" << r.stats.steps
                  << " rejected=" << r.stats.work.rejected_steps << " rhs_evaluations=" << r.stats.work.rhs_evaluations
                  << " cpu_seconds=" << format(r.cpu_seconds, 3) << " h_min=" << format(r.h_min, 3)
                  << " com_max_deviation=" << format(r.com_max_deviation, 3);
        if (euler) std::cout << " min_abs_sin_theta=" << format(r.min_abs_sin_theta, 3);
        std::cout << '\n';
        if (!r.stats.ok) std::cout << "  status: " << r.stats.status << '\n';
      }
      all[ci].push_back(std::move(r));
    }

    // This scene's group.
    const std::string base = "/scenes/" + sc.key;
    const hdf5::Handle g = h5.group(base);
    h5.text(g.get(), "scene_file", scene.file);
    h5.text(g.get(), "scene_name", scene.name);
    h5.text(g.get(), "scene_toml", scene.toml_text);
    h5.number(g.get(), "t_end", t_end);
    h5.number(g.get(), "tol", tol);
    h5.number(g.get(), "dt", dt);
    h5.numbers(g.get(), "center_of_mass_body", {chi.x(), chi.y(), chi.z()});
    {
      const hdf5::Handle gg = h5.group(base + "/grid");
      h5.dataset(gg.get(), "time", grid, {G}, "s");
    }
    {
      const hdf5::Handle rg = h5.group(base + "/reference");
      h5.text(rg.get(), "scheme", reference_scheme);
      h5.number(rg.get(), "tol", reference_tol);
      h5.dataset(rg.get(), "center_of_mass", ref, {G, 3}, "m");
    }
    const hdf5::Handle runs = h5.group(base + "/runs");
    for (const RunRecord& r : all[ci]) {
      const std::string p = base + "/runs/" + r.method.label;
      const hdf5::Handle rg = h5.group(p);
      const Method& m = r.method;
      h5.text(rg.get(), "method", m.name);
      h5.text(rg.get(), "family", m.baseline ? std::string("baseline") : m.scheme->family);
      h5.text(rg.get(), "coordinates", m.baseline ? bl::coordinates_name(m.id.coordinates) : "SO(3) x R^3");
      h5.text(rg.get(), "stepper", m.baseline ? bl::stepper_name(m.id.stepper) : m.name.c_str());
      h5.text(rg.get(), "guard", !m.baseline || m.id.coordinates != bl::Coordinates::euler_zxz ? "-"
                                 : m.guarded ? "on" : "off");
      if (m.adaptive) h5.number(rg.get(), "tol", tol);
      else h5.number(rg.get(), "dt", dt);
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
      if (m.baseline && m.id.coordinates == bl::Coordinates::euler_zxz) {
        h5.number(rg.get(), "min_abs_sin_theta", r.min_abs_sin_theta);
        const hdf5::Handle eg = h5.group(p + "/euler_zxz");
        const hsize_t n = r.e_time.size();
        h5.dataset(eg.get(), "time", r.e_time, {n}, "s");
        h5.dataset(eg.get(), "psi", r.psi, {n}, "rad");
        h5.dataset(eg.get(), "theta", r.theta, {n}, "rad");
        h5.dataset(eg.get(), "phi", r.phi, {n}, "rad");
        h5.dataset(eg.get(), "theta_dot", r.theta_dot, {n}, "s-1");
      }
      rows.push_back({sc.key, &r, tol, dt});
    }
    h5.flush();
  }

  // /results: one row per run, column datasets; the same table as the CSV.
  {
    const hdf5::Handle sg = h5.group("/results");
    std::vector<std::string> scene_col, method_col, coord_col, stepper_col, guard_col, outcome_col, status_col;
    std::vector<double> tol_col, dt_col, t_final, cpu, h_min, h_median, h_max, t_hmin, sin_min, com_dev;
    std::vector<std::int64_t> steps, rejected, rhs, compared;
    for (const auto& row : rows) {
      const RunRecord& r = *row.r;
      const Method& m = r.method;
      scene_col.push_back(row.scene);
      method_col.push_back(m.name);
      coord_col.push_back(m.baseline ? bl::coordinates_name(m.id.coordinates) : "lie-group");
      stepper_col.push_back(m.baseline ? std::string(bl::stepper_name(m.id.stepper)) : m.name);
      guard_col.push_back(!m.baseline || m.id.coordinates != bl::Coordinates::euler_zxz ? "-"
                          : m.guarded                                                 ? "on"
                                                                                      : "off");
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
  {
    const hdf5::Handle pg = h5.group("/parameters");
    h5.text(pg.get(), "command", "singularity");
    h5.text(pg.get(), "command_line", o.command_line);
    h5.number(pg.get(), "tol", tol_used);
    h5.number(pg.get(), "dt", dt_used);
    h5.integer(pg.get(), "quick", o.quick ? 1 : 0);
    h5.number(pg.get(), "grid_spacing", grid_spacing);
    h5.text(pg.get(), "reference_scheme", reference_scheme);
    h5.number(pg.get(), "reference_tol", reference_tol);
    h5.number(pg.get(), "euler_singular_threshold", bl::default_euler_singular_threshold);
    h5.number(pg.get(), "euler_fixed_step_resolution", bl::default_euler_fixed_step_resolution);
    h5.text(pg.get(), "csv_file", csv);
    for (const auto& [k, v] : hdf5::default_provenance(utc)) h5.text(pg.get(), k.c_str(), v);
  }
  h5.close();

  // The CSV beside it.
  {
    const std::string csv_partial = csv + ".partial";
    std::ofstream f(csv_partial);
    if (!f) throw OutputFileError("cannot write '" + csv_partial + "'");
    f << "scene,method,coordinates,stepper,guard,tol,dt,outcome,status,t_final,steps,rejected_steps,"
         "rhs_evaluations,cpu_seconds,h_min,h_median,h_max,t_at_h_min,min_abs_sin_theta,com_max_deviation,"
         "com_points_compared\n";
    for (const auto& row : rows) {
      const RunRecord& r = *row.r;
      const Method& m = r.method;
      f << row.scene << ',' << hdf5::csv_text(m.name) << ','
        << (m.baseline ? bl::coordinates_name(m.id.coordinates) : "lie-group") << ','
        << (m.baseline ? std::string(bl::stepper_name(m.id.stepper)) : m.name) << ','
        << (!m.baseline || m.id.coordinates != bl::Coordinates::euler_zxz ? "-" : m.guarded ? "on" : "off") << ','
        << (m.adaptive ? format(row.tol, 3) : "") << ',' << (m.adaptive ? "" : format(row.dt, 3)) << ','
        << (r.stats.ok ? "ok" : "failed") << ',' << hdf5::csv_text(r.stats.status) << ',' << format(r.stats.t_final, 10)
        << ',' << r.stats.steps << ',' << r.stats.work.rejected_steps << ',' << r.stats.work.rhs_evaluations << ','
        << format(r.cpu_seconds, 4) << ',' << format(r.h_min, 4) << ',' << format(r.h_median, 4) << ','
        << format(r.h_max, 4) << ',' << format(r.t_at_h_min, 8) << ',' << format(r.min_abs_sin_theta, 4) << ','
        << format(r.com_max_deviation, 4) << ',' << r.com_points << '\n';
    }
    f.close();
    if (!f) throw OutputFileError("cannot write '" + csv_partial + "'");
    hdf5::publish(csv_partial, csv, o.force, "the table is");
  }
  hdf5::publish(partial, o.out, o.force, "the study is");
  if (!o.quiet) std::cout << "wrote " << o.out << " and " << csv << '\n';
  return exit_ok;
}

}  // namespace

Subcommand add_singularity_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<SingularityOptions>();
  auto* sub = app.add_subcommand(
      "singularity",
      "The Euler-angle singularity study: every baseline and several Lie-group schemes on "
      "heavy_top_trindade_singular and heavy_top_trindade_4 (layout: experiments/SINGULARITY.md)");
  sub->add_option("--out", o->out, "Output file (HDF5); the same table as CSV goes beside it, .csv in place of .h5 (out.h5 -> out.csv)")->required();
  sub->add_option("--tol", o->tol, "Tolerance of the controlled steppers and adaptive schemes. Default: the scenes' [run] tol (1e-8)");
  sub->add_option("--dt", o->dt, "Step of the fixed-step steppers and schemes. Default: the scenes' [run] dt (1e-3)");
  sub->add_flag("--quick", o->quick, "A few methods over the first swings only (a CI check, seconds)");
  sub->add_option("--scenes-dir", o->scenes_dir,
                  "Folder of the shipped scenes. Default: LGI_SCENES_DIR, else found beside the lgi executable");
  sub->add_flag("--force", o->force, "Overwrite existing output files");
  sub->add_flag("--quiet", o->quiet, "Print nothing but errors");
  return {sub, [o, context] {
            o->command_line = context.command_line;
            return singularity(*o);
          }};
}

}  // namespace lgi::experiments

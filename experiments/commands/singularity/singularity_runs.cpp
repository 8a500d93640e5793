#include "experiments/commands/singularity/singularity_runs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lgi::experiments::singularity {

using integrators::Observer;
using integrators::RunConfig;
using integrators::RunStats;

namespace {

std::string label_of(std::string name) {
  for (char& c : name)
    if (c == '/' || c == ' ' || c == '(' || c == ')') c = '_';
  while (!name.empty() && name.back() == '_') name.pop_back();
  std::string out;
  for (char c : name)
    if (!(c == '_' && !out.empty() && out.back() == '_')) out += c;
  return out;
}

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

/// Centre of mass R χ at the grid times (every method observes exactly there:
/// RunConfig::output_times).
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
  RunConfig c = cfg;
  c.output_times = grid;        // every method observes exactly there (stepper_loop.hpp)
  c.chart_guards = m.guarded;   // off: the unguarded euler-zxz runs of the study
  return m.scheme->run(model, s, c, obs);
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

/// Largest distance of the run's centre of mass from the reference's over the grid points both reached.
void compare_with_reference(RunRecord& r, const std::vector<double>& ref, std::size_t G) {
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
}

}  // namespace

std::vector<Method> study_methods(bool quick, const system::AnyModel& model) {
  std::vector<Method> out;
  auto add_baseline = [&](bl::Coordinates c, bl::Stepper s, bool guarded) {
    Method m;
    m.baseline = true;
    m.id = {c, s};
    m.guarded = guarded;
    m.scheme = integrators::find_scheme(bl::baseline_name(c, s));
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

std::optional<std::vector<double>> reference_center_of_mass(const StudyScene& sc, const std::atomic<bool>* stop) {
  std::vector<double> ref(3 * sc.grid.size(), nan);
  Method m;
  m.scheme = integrators::find_scheme(reference_scheme);
  RunConfig cfg;
  cfg.t_end = sc.t_end;
  cfg.tol = reference_tol;
  cfg.stop = stop;
  State s = sc.scene->initial;
  GridObserver g(sc.grid, sc.chi, ref);
  if (run_method(m, sc.model, s, cfg, g, &sc.grid).interrupted) return std::nullopt;
  return ref;
}

std::optional<RunRecord> run_study_method(const Method& m, const StudyScene& sc, const std::vector<double>& reference,
                                          const std::atomic<bool>* stop) {
  RunRecord r;
  r.method = m;
  RunConfig cfg;
  cfg.t_end = sc.t_end;
  cfg.stop = stop;  // every step reads it (issue 50): a run cut by a signal is not a result
  if (m.adaptive) cfg.tol = sc.tol;
  else cfg.dt = sc.dt;
  const State initial = sc.scene->initial;
  // Timing: nothing observed in between.
  {
    State s = initial;
    RunConfig c = cfg;
    c.save_every = std::int64_t{1} << 62;
    integrators::NullObserver none;
    const RunStats timing = run_method(m, sc.model, s, c, none, nullptr);
    if (timing.interrupted) return std::nullopt;
    r.cpu_seconds = timing.cpu_seconds;
  }
  // History: every accepted step.
  {
    State s = initial;
    RunConfig c = cfg;
    c.save_every = 1;
    HistoryObserver h(r, sc.J_inv, is_euler(m));
    r.stats = run_method(m, sc.model, s, c, h, nullptr);
    if (r.stats.interrupted) return std::nullopt;
    step_statistics(r, h.times());
    if (is_euler(m)) {
      double mn = std::numeric_limits<double>::infinity();
      for (double th : r.theta) mn = std::min(mn, std::abs(std::sin(th)));
      r.min_abs_sin_theta = mn;
    }
  }
  // Centre of mass on the grid.
  r.com.assign(3 * sc.grid.size(), nan);
  {
    State s = initial;
    GridObserver g(sc.grid, sc.chi, r.com);
    if (run_method(m, sc.model, s, cfg, g, &sc.grid).interrupted) return std::nullopt;
  }
  compare_with_reference(r, reference, sc.grid.size());
  return r;
}

}  // namespace lgi::experiments::singularity

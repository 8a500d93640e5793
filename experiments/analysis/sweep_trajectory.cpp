#include "experiments/analysis/sweep_trajectory.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "experiments/analysis/cardan_invariants.hpp"
#include "experiments/io/scene_suspension.hpp"
#include "lie/quaternion.hpp"

namespace lgi::experiments {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

lie::Vec3 gamma_of(const system::State& x) { return x.R.transpose() * lie::Vec3::UnitZ(); }

/// The spec's surfaces: g = quantity[component] − value.
class SpecEvents final : public integrators::EventFunctions {
 public:
  SpecEvents(const std::vector<EventSpec>& events, const lie::Mat3& J_inv) : events_(events), J_inv_(J_inv) {}
  int count() const override { return static_cast<int>(events_.size()); }
  double value(int i, double, const system::State& x) const override {
    const EventSpec& e = events_[static_cast<std::size_t>(i)];
    const int k = e.component - 1;
    switch (e.quantity) {
      case EventSpec::Quantity::angular_momentum: return x.Pi(k) - e.value;
      case EventSpec::Quantity::angular_velocity: return (J_inv_ * x.Pi)(k) - e.value;
      case EventSpec::Quantity::gamma: return x.R(2, k) - e.value;  // Γ_k = (Rᵀe3)_k = R(2, k)
      case EventSpec::Quantity::gamma_rate: {  // d(Γ·e)/dt = (Γ × Ω)·e (docs/atlas.md §6)
        const lie::Vec3 g = gamma_of(x), w = J_inv_ * x.Pi;
        return g.cross(w).dot(lie::Vec3(e.axis[0], e.axis[1], e.axis[2])) - e.value;
      }
    }
    return 0.0;
  }
  int direction(int i) const override { return events_[static_cast<std::size_t>(i)].direction; }

 private:
  const std::vector<EventSpec>& events_;
  lie::Mat3 J_inv_;
};

/// The spec's surfaces on a Cardan top: the same functions of the body's
/// state (R(q), Π = J E q̇; docs/cardan.md §7), so a row's crossings mean what
/// they mean on SO(3) × ℝ³.
class CardanSpecEvents final : public integrators::BasicEventFunctions<system::TorusState> {
 public:
  CardanSpecEvents(const SpecEvents& body, const system::CardanTop& top) : body_(body), top_(top) {}
  int count() const override { return body_.count(); }
  double value(int i, double t, const system::TorusState& x) const override {
    return body_.value(i, t, top_.body_state(x));
  }
  int direction(int i) const override { return body_.direction(i); }

 private:
  const SpecEvents& body_;
  const system::CardanTop& top_;
};

/// The body's state of a sample: itself on SO(3) × ℝ³, R(q) and Π on T³ × ℝ³.
inline const system::State& body_of(const system::State& x, const system::CardanTop*) { return x; }
inline system::State body_of(const system::TorusState& x, const system::CardanTop* top) { return top->body_state(x); }

/// Largest invariant errors over the observed samples; crossings as rows. On
/// a Cardan top (S = TorusState) the rows hold the body's state, the errors
/// those of CardanInvariants.
template <class S, class Invariants>
class SweepObserver final : public integrators::BasicObserver<S> {
 public:
  SweepObserver(const Invariants& invariants, const std::vector<int>& error_slots, std::int64_t index,
                std::int64_t max_events, std::int64_t trajectory_every, std::vector<double>& events,
                std::vector<double>& max_errors, std::vector<double>& scratch)
      : invariants_(invariants),
        trajectory_every_(trajectory_every),
        slots_(error_slots),
        index_(index),
        max_events_(max_events),
        events_(events),
        max_(max_errors),
        errors_(scratch) {}
  SweepObserver(const Invariants& invariants, const system::CardanTop* top, const std::vector<int>& error_slots,
                std::int64_t index, std::int64_t max_events, std::int64_t trajectory_every, std::vector<double>& events,
                std::vector<double>& max_errors, std::vector<double>& scratch)
      : SweepObserver(invariants, error_slots, index, max_events, trajectory_every, events, max_errors, scratch) {
    top_ = top;
  }

  void observe(std::int64_t step, double t, const S& x) override {
    if (trajectory_every_ > 0 && step % trajectory_every_ == 0) sample(step, t, x);
    const auto v = invariants_.evaluate(x);
    if (!have_initial_) {
      initial_ = v;
      have_initial_ = true;
    }
    invariants_.errors(initial_, v, errors_);
    for (std::size_t k = 0; k < slots_.size(); ++k) {
      if (slots_[k] < 0) continue;
      const double e = errors_[static_cast<std::size_t>(slots_[k])];
      // NaN propagates: a non-finite error is the largest.
      if (std::isnan(e) || e > max_[k]) max_[k] = e;
    }
  }
  void on_event(const integrators::BasicEventHit<S>& hit) override {
    ++count_;
    if (count_ > max_events_) return;
    append(hit.event, hit.direction, hit.step, hit.t, body_of(hit.state, top_));
  }
  /// A state of the thinned trajectory (trajectory_every).
  void sample(std::int64_t step, double t, const S& x) {
    append(sample_row, 0, step, t, body_of(x, top_));
    ++samples_;
    last_sample_ = step;
  }
  std::int64_t crossings() const { return count_; }
  std::int64_t samples() const { return samples_; }
  std::int64_t last_sample() const { return last_sample_; }

 private:
  void append(int event, int direction, std::int64_t step, double t, const system::State& x) {
    const auto q = lie::to_wxyz(lie::quat_from_matrix(x.R));
    const lie::Vec3 g = gamma_of(x);
    const double row[event_row_width] = {static_cast<double>(index_), static_cast<double>(event),
                                         static_cast<double>(direction), static_cast<double>(step), t,
                                         x.Pi.x(), x.Pi.y(), x.Pi.z(), q[0], q[1], q[2], q[3], g.x(), g.y(), g.z()};
    events_.insert(events_.end(), row, row + event_row_width);
  }
  const Invariants& invariants_;
  const system::CardanTop* top_ = nullptr;  // on T³ × ℝ³: R(q) and Π of each sample
  std::int64_t trajectory_every_, samples_ = 0, last_sample_ = -1;
  const std::vector<int>& slots_;
  std::int64_t index_, max_events_, count_ = 0;
  std::vector<double>& events_;
  std::vector<double>& max_;
  bool have_initial_ = false;
  decltype(std::declval<const Invariants&>().evaluate(std::declval<const S&>())) initial_{};
  std::vector<double>& errors_;  // the runner's, reused (no allocation per trajectory)
};

using BodyObserver = SweepObserver<system::State, system::SceneInvariants>;
using CardanSweepObserver = SweepObserver<system::TorusState, CardanInvariants>;

}  // namespace

struct SweepRunner::Context {
  system::Scene scene;
  system::AnyModel model;
  system::SceneInvariants invariants;
  SpecEvents events;
  // A Cardan scene (T³ × ℝ³, docs/cardan.md §7): its top, invariants and
  // events; the scheme's run_cardan runs it on the one time loop.
  std::optional<system::CardanTop> cardan;
  std::optional<CardanInvariants> cardan_invariants;
  std::optional<CardanSpecEvents> cardan_events;
  std::vector<int> error_slots;  // for each sweep error column, its index in invariants.error_names() (−1: none)
  std::string refusal;           // why the scheme cannot run on this model (empty: it can)
  std::vector<double> inputs;    // the inputs it was built for
  std::optional<integrators::ensemble::EnsembleStepper> ensemble;  // where run_next() may batch trajectories
  Context(system::Scene s, const std::vector<EventSpec>& spec_events, const std::vector<std::string>& error_names)
      : scene(std::move(s)),
        model(system::make_model(scene)),
        invariants(scene, model),
        events(spec_events, scene.inertia.inverse()) {
    if (scene.suspension) {
      cardan.emplace(cardan_top(scene));
      cardan_invariants.emplace(*cardan);
      cardan_events.emplace(events, *cardan);
    }
    const auto names = cardan ? cardan_invariants->error_names() : invariants.error_names();
    for (const auto& n : error_names) {
      const auto it = std::find(names.begin(), names.end(), n);
      error_slots.push_back(it == names.end() ? -1 : static_cast<int>(it - names.begin()));
    }
  }
};

SweepRunner::SweepRunner(const SweepSpec& spec, const SweepPlan& plan, const integrators::SchemeInfo& scheme,
                         const integrators::RunConfig& base_config, const std::vector<std::string>& error_names)
    : spec_(spec),
      plan_(plan),
      scheme_(scheme),
      config_(base_config),
      error_names_(error_names),
      rows_(integrators::ensemble::max_lanes),
      states_(integrators::ensemble::max_lanes),
      stats_(integrators::ensemble::max_lanes),
      lane_events_(integrators::ensemble::max_lanes) {}

SweepRunner::~SweepRunner() = default;

void SweepRunner::prepare(std::int64_t i) {
  plan_.inputs(i, inputs_);
  if (!context_ || !plan_.same_scene(context_->inputs, inputs_)) {
    context_.reset();
    context_ = std::make_unique<Context>(plan_.scene(inputs_), spec_.events, error_names_);
    context_->inputs = inputs_;
    if (!context_->cardan)
      context_->refusal = integrators::unsupported_reason(scheme_, context_->model);
    else if (!scheme_.run_cardan)
      context_->refusal = "scheme '" + scheme_.name + "' runs on SO(3) x R^3 scenes only (this scene is a Cardan top)";
    const auto isa = integrators::ensemble::sweep_isa();
    if (isa && context_->refusal.empty() && !context_->cardan && !scheme_.properties.adaptive && config_.dt > 0.0)
      context_->ensemble = integrators::ensemble::EnsembleStepper::make(scheme_, context_->model, *isa);
  }
}

void SweepRunner::run(std::int64_t i, std::vector<double>& events, const std::atomic<bool>* stop, TrajectoryRow& row) {
  const auto start = std::chrono::steady_clock::now();
  run_timed(i, events, stop, row);
  row.cpu_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Trajectory i's row before its run, and its initial state; false if it
/// has no run (its set-up failed, or the scheme refuses the scene): then the
/// row is complete.
bool SweepRunner::begin_row(std::int64_t i, TrajectoryRow& row, system::State& x) {
  row.index = i;
  row.status = sweep_ok;
  row.reason.clear();
  row.steps = row.rejected_steps = row.event_count = row.sample_count = 0;
  row.t_final = 0.0;
  row.interrupted = false;
  row.max_errors.assign(error_names_.size(), nan);
  row.angular_momentum.fill(nan), row.gamma.fill(nan), row.orientation.fill(nan);
  try {
    prepare(i);
    x = plan_.initial_state(i, context_->scene, inputs_);
  } catch (const std::exception& e) {  // an invalid varied scene, an empty level set
    row.inputs = inputs_;
    row.status = sweep_setup_failed;
    row.reason = e.what();
    return false;
  }
  row.inputs = inputs_;
  if (!context_->refusal.empty()) {
    row.status = sweep_setup_failed;
    row.reason = context_->refusal;
    return false;
  }
  std::fill(row.max_errors.begin(), row.max_errors.end(), 0.0);
  for (std::size_t k = 0; k < row.max_errors.size(); ++k)
    if (context_->error_slots[k] < 0) row.max_errors[k] = nan;
  return true;
}

namespace {

/// The rest of a row once its run ended: the final state, the counts and the status.
template <class S, class Invariants>
void finish_row(const SweepSpec& spec, const integrators::RunStats& stats, const S& final_state,
                SweepObserver<S, Invariants>& observer, const system::CardanTop* top, std::size_t events_before,
                const std::vector<double>& events, TrajectoryRow& row) {
  row.interrupted = stats.interrupted;
  row.steps = stats.steps;
  row.rejected_steps = stats.work.rejected_steps;
  row.t_final = stats.t_final;
  // The thinned trajectory ends with the final state.
  if (spec.trajectory_every > 0 && observer.last_sample() != stats.steps)
    observer.sample(stats.steps, stats.t_final, final_state);
  const system::State x = body_of(final_state, top);
  row.sample_count = observer.samples();
  row.event_count = static_cast<std::int64_t>((events.size() - events_before) / event_row_width) - row.sample_count;
  std::copy(x.Pi.data(), x.Pi.data() + 3, row.angular_momentum.begin());
  const lie::Vec3 g = gamma_of(x);
  std::copy(g.data(), g.data() + 3, row.gamma.begin());
  row.orientation = lie::to_wxyz(lie::quat_from_matrix(x.R));
  if (!stats.ok) {
    row.status = sweep_run_failed;
    row.reason = stats.status;
  } else if (observer.crossings() > spec.max_events) {
    row.status = sweep_events_truncated;
    row.reason = std::to_string(observer.crossings()) + " crossings, more than max_events = " +
                 std::to_string(spec.max_events) + "; the first " + std::to_string(spec.max_events) + " kept";
  }
}

}  // namespace

void SweepRunner::run_timed(std::int64_t i, std::vector<double>& events, const std::atomic<bool>* stop,
                            TrajectoryRow& row) {
  system::State x;
  if (!begin_row(i, row, x)) return;
  if (context_->cardan) return run_cardan(i, events, stop, row);
  const std::size_t events_before = events.size();
  BodyObserver observer(context_->invariants, context_->error_slots, i, spec_.max_events, spec_.trajectory_every,
                         events, row.max_errors, scratch_);
  integrators::RunConfig cfg = config_;
  cfg.stop = stop;
  cfg.cpu_clock = false;  // timed by run() and the chunk (sweep_trajectory.hpp)
  if (!spec_.events.empty()) cfg.events = &context_->events;
  const integrators::RunStats stats = scheme_.run(context_->model, x, cfg, observer);
  finish_row(spec_, stats, x, observer, nullptr, events_before, events, row);
}

/// run_timed() on a Cardan scene: from the scene's state on T³ × ℝ³ (its
/// body, suspension and term keys varied), by the scheme's run_cardan.
void SweepRunner::run_cardan(std::int64_t i, std::vector<double>& events, const std::atomic<bool>* stop,
                             TrajectoryRow& row) {
  const Context& c = *context_;
  const std::size_t events_before = events.size();
  CardanSweepObserver observer(*c.cardan_invariants, &*c.cardan, c.error_slots, i, spec_.max_events,
                          spec_.trajectory_every, events, row.max_errors, scratch_);
  auto cfg = integrators::run_config_with<system::TorusState>(config_);
  cfg.stop = stop;
  cfg.cpu_clock = false;
  if (!spec_.events.empty()) cfg.events = &*c.cardan_events;
  system::TorusState x = c.scene.cardan_initial;
  const integrators::RunStats stats = scheme_.run_cardan(*c.cardan, x, cfg, observer);
  finish_row(spec_, stats, x, observer, &*c.cardan, events_before, events, row);
}

int SweepRunner::run_next(std::int64_t i, std::int64_t limit, std::vector<double>& events,
                          const std::atomic<bool>* stop) {
  const auto start = std::chrono::steady_clock::now();
  int n = 1;
  if (limit > 1 && integrators::ensemble::sweep_isa()) {
    n = run_ensemble(i, limit, events, stop);
  } else {
    run_timed(i, events, stop, rows_[0]);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (int j = 0; j < n; ++j) rows_[static_cast<std::size_t>(j)].cpu_seconds = seconds / n;
  return n;
}

/// run_next() with the ensemble path: trajectory i first (alone, by
/// run_timed, unless its scene has an ensemble), then the following ones
/// while they share its scene and lanes remain. A trajectory whose set-up
/// fails takes a row and no lane.
int SweepRunner::run_ensemble(std::int64_t i, std::int64_t limit, std::vector<double>& events,
                              const std::atomic<bool>* stop) {
  system::State x;
  const bool first_runs = begin_row(i, rows_[0], x);
  if (!first_runs || !context_->ensemble || context_->ensemble->lanes() < 2) {
    if (first_runs) run_timed(i, events, stop, rows_[0]);  // begins the row again: the same row
    return 1;
  }
  integrators::ensemble::EnsembleStepper& ensemble = *context_->ensemble;
  const std::size_t lanes = static_cast<std::size_t>(ensemble.lanes());
  int rows = 0;
  std::size_t used = 0;
  int lane_of_row[integrators::ensemble::max_lanes];
  std::optional<BodyObserver> observers[integrators::ensemble::max_lanes];
  integrators::Observer* observer_of_lane[integrators::ensemble::max_lanes];
  auto add_lane = [&](std::int64_t index, TrajectoryRow& row, const system::State& initial) {
    std::vector<double>& buffer = lane_events_[used];
    buffer.clear();
    observers[used].emplace(context_->invariants, context_->error_slots, index, spec_.max_events,
                            spec_.trajectory_every, buffer, row.max_errors, scratch_);
    observer_of_lane[used] = &*observers[used];
    states_[used] = initial;
    lane_of_row[rows] = static_cast<int>(used++);
  };
  add_lane(i, rows_[0], x);
  ++rows;
  std::vector<double>& next_inputs = scratch_inputs_;
  for (std::int64_t j = i + 1; j < i + limit && used < lanes && rows < integrators::ensemble::max_lanes; ++j) {
    plan_.inputs(j, next_inputs);
    if (!plan_.same_scene(context_->inputs, next_inputs)) break;
    TrajectoryRow& row = rows_[static_cast<std::size_t>(rows)];
    lane_of_row[rows] = -1;
    if (begin_row(j, row, x)) add_lane(j, row, x);
    ++rows;
  }
  integrators::RunConfig cfg = config_;
  cfg.stop = stop;
  cfg.cpu_clock = false;
  if (!spec_.events.empty()) cfg.events = &context_->events;
  integrators::ensemble::run_ensemble(ensemble, context_->model, {states_.data(), used}, cfg, {observer_of_lane, used},
                                      {stats_.data(), used}, workspace_);
  for (int r = 0; r < rows; ++r) {
    const int lane = lane_of_row[r];
    if (lane < 0) continue;
    const auto l = static_cast<std::size_t>(lane);
    finish_row(spec_, stats_[l], states_[l], *observers[l], nullptr, 0, lane_events_[l], rows_[static_cast<std::size_t>(r)]);
    events.insert(events.end(), lane_events_[l].begin(), lane_events_[l].end());
  }
  return rows;
}

}  // namespace lgi::experiments

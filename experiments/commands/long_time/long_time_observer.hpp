#pragma once
// lgi long-time's observer (long_time_command.cpp): the log-spaced sample
// schedule, the progress bar, and the observer that keeps the error maxima
// between samples, on either state space.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "experiments/io/results_file.hpp"
#include "experiments/io/run_checkpoint.hpp"
#include "integrators/core/run_config.hpp"

namespace lgi::experiments {

/// The sample steps: 0, round(10^(j/N)) for j = 0, 1, ... (each taken once),
/// and the last step (known for fixed-step runs; adaptive runs add it after
/// the run).
class SampleSchedule {
 public:
  SampleSchedule(int per_decade, std::int64_t last) : per_decade_(per_decade), last_(last) {}
  std::int64_t first() const { return 0; }
  std::int64_t last() const { return last_; }
  /// The next sample step after `step`.
  std::int64_t next(std::int64_t step) {
    for (;;) {
      const double x = std::round(std::pow(10.0, static_cast<double>(j_) / per_decade_));
      if (x > 9.0e18) return std::numeric_limits<std::int64_t>::max();
      const auto k = static_cast<std::int64_t>(x);
      if (k > step) return last_ > 0 ? std::min(k, last_) : k;
      ++j_;
    }
  }

 private:
  int per_decade_;
  std::int64_t last_;  // <= 0: unknown
  long j_ = 0;
};

/// A progress bar on stderr with the time left, shown once the run is
/// expected to take more than about a second.
class Progress {
 public:
  explicit Progress(bool enabled) : enabled_(enabled), start_(std::chrono::steady_clock::now()) {}
  /// fraction in [0, 1].
  void update(double fraction, std::int64_t step) {
    if (!enabled_ || !(fraction > 0.0)) return;
    const auto now = std::chrono::steady_clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    if (!shown_) {
      if (elapsed < 0.25 || elapsed / fraction < 1.0) return;
      shown_ = true;
    } else if (std::chrono::duration<double>(now - last_draw_).count() < 0.2) {
      return;
    }
    last_draw_ = now;
    const double left = elapsed / fraction - elapsed;
    constexpr int width = 30;
    const int filled = std::clamp(static_cast<int>(fraction * width), 0, width);
    std::string bar(static_cast<std::size_t>(filled), '=');
    bar.resize(width, ' ');
    std::fprintf(stderr, "\r\033[K[%s] %5.1f%%  step %lld  %s left", bar.c_str(), 100.0 * fraction,
                 static_cast<long long>(step), duration(left).c_str());
    std::fflush(stderr);
  }
  void done() {
    if (shown_) {
      std::fprintf(stderr, "\r\033[K");
      std::fflush(stderr);
    }
  }

 private:
  static std::string duration(double s) {
    char buf[32];
    if (s < 10) std::snprintf(buf, sizeof buf, "%.1f s", s);
    else if (s < 60) std::snprintf(buf, sizeof buf, "%.0f s", s);
    else if (s < 3600) std::snprintf(buf, sizeof buf, "%d min %02d s", static_cast<int>(s / 60), static_cast<int>(s) % 60);
    else std::snprintf(buf, sizeof buf, "%d h %02d min", static_cast<int>(s / 3600), static_cast<int>(s / 60) % 60);
    return buf;
  }
  bool enabled_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

/// Receives every step of a run on states S: evaluates the invariants,
/// keeps the running maximum of every error since the last sample, and emits
/// a row at the sample steps (top of long_time_command.cpp). Invariants has
/// evaluate(const S&) and errors(initial, values, out): the scene's
/// (system::SceneInvariants) on SO(3) × ℝ³, CardanInvariants on T³ × ℝ³.
template <class S, class Invariants>
class LongTimeObserver final : public integrators::BasicObserver<S> {
 public:
  LongTimeObserver(const Invariants& invariants, ResultsFile& file, std::vector<std::string> names,
                   int per_decade, std::int64_t last_step, double t0, double t_end, Progress& progress)
      : invariants_(invariants),
        file_(file),
        names_(std::move(names)),
        schedule_(per_decade, last_step),
        last_step_(last_step),
        t0_(t0),
        t_end_(t_end),
        progress_(progress),
        current_(names_.size(), 0.0),
        window_max_(names_.size(), 0.0),
        run_max_(names_.size(), 0.0),
        per_decade_(per_decade) {
    next_sample_ = schedule_.first();
  }

  void observe(std::int64_t step, double t, const S& s) override {
    const Values v = invariants_.evaluate(s);
    if (!have_initial_) {
      initial_ = v;
      have_initial_ = true;
    }
    invariants_.errors(initial_, v, current_);
    for (std::size_t i = 0; i < current_.size(); ++i)
      if (!(window_max_[i] >= current_[i])) window_max_[i] = current_[i];
    step_ = step;
    time_ = t;
    emitted_ = false;
    if (step >= next_sample_) {
      emit();
      next_sample_ = schedule_.next(step);
    }
    if ((step & 4095) == 0) [[unlikely]]
      housekeeping();
    // A run ended by RunConfig::stop observes its final state right after
    // on_stop(): that state is the last sample.
    if (stopping_ && !emitted_) [[unlikely]]
      emit();
  }
  void on_stop() override { stopping_ = true; }

  /// Rows are flushed with the checkpoints (LongTimeCheckpoints), not here.
  void flush_with_checkpoints() { checkpointing_ = true; }
  /// A resumed run: where the run was at checkpoint c, whose initial state was `initial`.
  void resume_at(const BasicRunCheckpoint<S>& c, const S& initial) {
    initial_ = invariants_.evaluate(initial);
    have_initial_ = true;
    window_max_ = c.window_max;
    run_max_ = c.run_max;
    step_ = c.loop.step;
    time_ = c.loop.t;
    emitted_ = true;
    schedule_ = SampleSchedule(per_decade_, schedule_.last());
    next_sample_ = schedule_.next(step_);
  }
  /// The command's part of a checkpoint.
  void fill(BasicRunCheckpoint<S>& c) const {
    c.window_max = window_max_;
    c.run_max = run_max_;
  }

  /// Emits a row for the last observed step unless it is already a sample.
  void finish() {
    if (step_ >= 0 && !emitted_) emit();
  }
  std::int64_t last_observed_step() const { return step_; }
  double last_observed_time() const { return time_; }
  const std::vector<double>& current() const { return current_; }
  const std::vector<double>& run_max() const { return run_max_; }

 private:
  void emit() {
    ResultRow row = file_.row();
    row.set("step", step_);
    row.set("time", time_);
    for (std::size_t i = 0; i < names_.size(); ++i) {
      row.set(names_[i], current_[i]);
      row.set(names_[i] + "_window_max", window_max_[i]);
      run_max_[i] = std::max(run_max_[i], window_max_[i]);
      window_max_[i] = 0.0;
    }
    file_.append(row);
    emitted_ = true;
  }
  void housekeeping() {
    if (!checkpointing_) file_.flush_if_due();
    const double fraction = last_step_ > 0 ? static_cast<double>(step_) / static_cast<double>(last_step_)
                                           : (time_ - t0_) / (t_end_ - t0_);
    progress_.update(fraction, step_);
  }

  using Values = std::decay_t<decltype(std::declval<const Invariants&>().evaluate(std::declval<const S&>()))>;
  const Invariants& invariants_;
  ResultsFile& file_;
  std::vector<std::string> names_;  // the error columns, e.g. "energy_error"
  SampleSchedule schedule_;
  std::int64_t last_step_;
  double t0_, t_end_;
  Progress& progress_;
  bool have_initial_ = false;
  Values initial_{};
  std::vector<double> current_, window_max_, run_max_;
  std::int64_t next_sample_ = 0;
  std::int64_t step_ = -1;
  double time_ = 0.0;
  bool emitted_ = false;
  bool stopping_ = false;
  bool checkpointing_ = false;
  int per_decade_;
};

}  // namespace lgi::experiments

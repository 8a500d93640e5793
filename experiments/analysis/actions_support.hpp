#pragma once
// Pieces shared by actions_measure.cpp and actions_torus.cpp: one event
// function given as a callable, an observer that records its located
// crossings and stops the run after enough of them, and the weight of the
// weighted Birkhoff average (docs/actions.md §3).
#include <atomic>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "integrators/core/events.hpp"
#include "integrators/core/run_config.hpp"
#include "integrators/system/scene.hpp"
#include "experiments/io/trajectory_observer.hpp"  // interrupt_requested

namespace lgi::experiments {

/// The surface g(x) = 0, rising crossings only.
class RisingEvent final : public integrators::EventFunctions {
 public:
  explicit RisingEvent(std::function<double(const system::State&)> g) : g_(std::move(g)) {}
  int count() const override { return 1; }
  double value(int, double, const system::State& x) const override { return g_(x); }
  int direction(int) const override { return 1; }

 private:
  std::function<double(const system::State&)> g_;
};

/// Records the crossings of a RisingEvent; sets the stop flag at the `wanted`-th,
/// and at a signal (interrupt_requested: Ctrl-C ends a long torus run within a step;
/// the run then has too few crossings and its torus fails).
/// Subclasses that also keep the step samples override observe() and call poll_interrupt().
class CrossingRecorder : public integrators::Observer {
 public:
  CrossingRecorder(std::function<double(const system::State&)> g, int wanted) : event_(std::move(g)), wanted_(wanted) {}
  void observe(std::int64_t, double, const system::State&) override { poll_interrupt(); }
  void on_event(const integrators::EventHit& hit) override {
    hits_.push_back(hit);
    if (static_cast<int>(hits_.size()) >= wanted_) stop_.store(true);
  }
  const integrators::EventFunctions& events() const { return event_; }
  const std::atomic<bool>* stop_flag() const { return &stop_; }
  const std::vector<integrators::EventHit>& hits() const { return hits_; }
  /// Asks for more crossings: the run can be continued from where it stopped.
  void extend(int wanted) {
    wanted_ = wanted;
    stop_.store(false);
  }

 protected:
  void poll_interrupt() {
    if (interrupt_requested.load(std::memory_order_relaxed)) stop_.store(true, std::memory_order_relaxed);
  }

 private:
  RisingEvent event_;
  int wanted_;
  std::atomic<bool> stop_{false};
  std::vector<integrators::EventHit> hits_;
};

/// The mean period of the rising crossings of g = 0 over `periods` periods,
/// on the orbit of x0 integrated with `scheme` at step dt (NaN if fewer
/// crossings occur before max_time).
double crossing_period(const system::Scene& scene, const system::State& x0, const std::string& scheme, double dt,
                       const std::function<double(const system::State&)>& g, int periods, double max_time);

/// The weight exp(−1/(s(1 − s))) of the weighted Birkhoff average on (0, 1)
/// (Das, Saiki, Sander & Yorke, Nonlinearity 30 (2017) 4111), 0 outside,
/// and its derivative.
inline double birkhoff_weight(double s) { return s > 0.0 && s < 1.0 ? std::exp(-1.0 / (s * (1.0 - s))) : 0.0; }
inline double birkhoff_weight_derivative(double s) {
  return s > 0.0 && s < 1.0 ? birkhoff_weight(s) * (1.0 - 2.0 * s) / (s * s * (1.0 - s) * (1.0 - s)) : 0.0;
}

/// The weighted Birkhoff average of values f_0 .. f_{n−1} (weights at (k + 1)/(n + 1)).
inline double birkhoff_average(const std::vector<double>& f) {
  double num = 0.0, den = 0.0;
  const double n = static_cast<double>(f.size());
  for (std::size_t k = 0; k < f.size(); ++k) {
    const double w = birkhoff_weight((static_cast<double>(k) + 1.0) / (n + 1.0));
    num += w * f[k];
    den += w;
  }
  return den > 0.0 ? num / den : std::nan("");
}

}  // namespace lgi::experiments

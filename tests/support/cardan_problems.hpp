#pragma once
// Cardan-top problems and a run helper for the tests of the T³ schemes
// (tests/test_cardan_*.cpp).
#include <vector>

#include "integrators/registry/torus_registry.hpp"

namespace lgi::testing {

/// A top with massive rings, an off-axis centre of mass and a ring centre
/// off the axes: every term of M(q) and V(q) is exercised; H is not
/// separable. tilt = 0 makes q1 cyclic.
inline system::CardanTop cardan_test_top(double tilt) {
  system::CardanTop top;
  top.J << 0.9, 0.05, 0.0, 0.05, 1.0, 0.02, 0.0, 0.02, 1.3;
  top.mass = 1.0;
  top.chi = lie::Vec3(0.3, 0.2, 0.6);
  top.g = 1.0;
  top.suspension.tilt = tilt;
  top.suspension.outer_inertia = 0.2;
  top.suspension.inner_inertia = lie::Vec3(0.1, 0.15, 0.12);
  top.suspension.inner_mass = 0.3;
  top.suspension.inner_center = lie::Vec3(0.05, 0.0, 0.1);
  top.suspension.outer_mass = 0.4;
  top.suspension.outer_center = lie::Vec3(0.0, 0.1, 0.2);
  return top;
}

inline system::TorusState cardan_test_initial(const system::CardanTop& top) {
  return top.from_rates(lie::Vec3(0.3, 1.2, 0.5), lie::Vec3(0.5, -0.4, 3.0));
}

/// Keeps every sample (or only the last one).
class KeepSamples final : public integrators::TorusObserver {
 public:
  explicit KeepSamples(bool all = false) : all_(all) {}
  void observe(std::int64_t, double t, const system::TorusState& s) override {
    if (!all_) times.clear(), states.clear();
    times.push_back(t);
    states.push_back(s);
  }
  std::vector<double> times;
  std::vector<system::TorusState> states;

 private:
  bool all_;
};

/// The T³ scheme named `name` (its registry entry).
inline const integrators::SchemeInfo& cardan_scheme(const char* name) {
  return *integrators::find_cardan_scheme(name);
}

/// Runs a registered T³ scheme from x0 over [0, t_end]: fixed step dt, or
/// the adaptive control with tol. Returns the statistics; x0 becomes the final state.
inline integrators::RunStats run_torus(const integrators::SchemeInfo& scheme, const system::CardanTop& top,
                                       system::TorusState& x, double t_end, double dt, double tol = 0.0,
                                       integrators::TorusObserver* observer = nullptr) {
  integrators::TorusRunConfig cfg;
  cfg.t_end = t_end;
  cfg.dt = dt;
  cfg.tol = tol;
  cfg.cpu_clock = false;
  KeepSamples last;
  return scheme.run_cardan(top, x, cfg, observer ? *observer : last);
}

/// The state at t_end from cardan_test_initial: cardan-rk4 with h = 5e-5
/// (an error below 1e-13 at t_end = 2).
inline system::TorusState cardan_reference(const system::CardanTop& top, double t_end) {
  system::TorusState x = cardan_test_initial(top);
  run_torus(cardan_scheme("cardan-rk4"), top, x, t_end, 5e-5);
  return x;
}

inline double state_distance(const system::TorusState& a, const system::TorusState& b) {
  return ((system::stack(a) - system::stack(b)).array().abs() / (1.0 + system::stack(b).array().abs())).maxCoeff();
}

}  // namespace lgi::testing

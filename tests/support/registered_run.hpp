#pragma once
// Running a registered scheme the way `lgi simulate` does (through its
// SchemeInfo::run), for the tests: one fixed-step run from x0 to t_end, the
// final state and the run's statistics, nothing observed unless asked.
#include <catch2/catch.hpp>
#include <cstdint>
#include <string>

#include "integrators/registry/registry.hpp"

namespace lgi::testing {

struct RegisteredRun {
  system::State state;
  integrators::RunStats stats;
};

/// The registry's entry for `name`; the test fails if there is none.
inline const integrators::SchemeInfo& registered_scheme(const std::string& name) {
  const integrators::SchemeInfo* s = integrators::find_scheme(name);
  INFO("scheme " << name);
  REQUIRE(s != nullptr);
  return *s;
}

inline RegisteredRun run_registered(const integrators::SchemeInfo& scheme, const system::AnyModel& model,
                                    const system::State& x0, double t_end, double h,
                                    integrators::Observer* observer = nullptr,
                                    std::int64_t save_every = std::int64_t{1} << 30) {
  RegisteredRun r{x0, {}};
  integrators::RunConfig cfg;
  cfg.t_end = t_end;
  cfg.dt = h;
  cfg.save_every = save_every;
  integrators::NullObserver none;
  r.stats = scheme.run(model, r.state, cfg, observer ? *observer : none);
  return r;
}

inline RegisteredRun run_registered(const std::string& name, const system::AnyModel& model, const system::State& x0,
                                    double t_end, double h, integrators::Observer* observer = nullptr,
                                    std::int64_t save_every = std::int64_t{1} << 30) {
  return run_registered(registered_scheme(name), model, x0, t_end, h, observer, save_every);
}

/// The final state of a run that must succeed.
inline system::State final_state_ok(const integrators::SchemeInfo& scheme, const system::AnyModel& model,
                                    const system::State& x0, double t_end, double h) {
  const RegisteredRun r = run_registered(scheme, model, x0, t_end, h);
  INFO(scheme.name << " at h = " << h << ": " << r.stats.status);
  REQUIRE(r.stats.ok);
  return r.state;
}

}  // namespace lgi::testing

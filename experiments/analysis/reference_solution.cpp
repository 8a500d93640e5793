#include "experiments/analysis/reference_solution.hpp"

#include <algorithm>
#include <cmath>

#include "experiments/errors/exit_status.hpp"
#include "experiments/io/number_format.hpp"
#include "integrators/system/free_body_exact.hpp"
#include "lie/so3.hpp"

namespace lgi::experiments {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

/// Keeps only the latest state; the registry's runs call it at step 0 and at
/// the final step (save_every is larger than any run).
class FinalStateObserver final : public integrators::Observer {
 public:
  void observe(std::int64_t step, double t, const system::State& s) override {
    last_step = step;
    last_time = t;
    last = s;
  }
  std::int64_t last_step = -1;
  double last_time = 0.0;
  system::State last{};
};

/// The conditioning floor of an exact reference: the larger of
///  - the spread at t_end of exact flows from initial states perturbed at
///    round-off (δ = 1e-15 relative, R → R exp(δ e_j), Π → Π + δ|Π| e_j), and
///  - the flow's own consistency, |E_T(x0) − E_{T−s}(E_s(x0))| for s = T/3,
///    T/2: the evaluation error of the elliptic functions, which near a
///    separatrix (modulus near 1) exceeds the perturbation spread by far.
struct ExactFloor {
  double floor = 0.0;          // the reference's estimated error
  double amplification = 0.0;  // κ: spread at t_end per unit relative perturbation of the initial state
};

ExactFloor exact_conditioning_floor(const system::Inertia& inertia, const system::State& initial,
                                   const system::State& exact_end, double t_end) {
  constexpr double delta = 1e-15;
  double floor = 0.0;
  auto widen = [&](double d) {
    if (!(d <= floor)) floor = d;  // NaN propagates
  };
  for (int j = 0; j < 6; ++j) {
    system::State x = initial;
    if (j < 3) x.R = initial.R * lie::exp_so3(delta * lie::Vec3::Unit(j));
    else x.Pi += delta * initial.Pi.norm() * lie::Vec3::Unit(j - 3);
    widen(global_error(system::FreeBodyExactFlow(inertia, x).at(t_end), exact_end).max);
  }
  const double amplification = floor / delta;
  const system::FreeBodyExactFlow from_initial(inertia, initial);
  for (const double s : {t_end / 3.0, t_end / 2.0}) {
    const system::State midway = from_initial.at(s);
    widen(global_error(system::FreeBodyExactFlow(inertia, midway).at(t_end - s), exact_end).max);
  }
  return {floor, amplification};
}

}  // namespace

GlobalError global_error(const system::State& s, const system::State& ref) {
  GlobalError e;
  if (!s.R.allFinite() || !s.Pi.allFinite()) return e;
  e.attitude = lie::geodesic_distance(ref.R, s.R);
  const double pn = ref.Pi.norm();
  const double d = (s.Pi - ref.Pi).norm();
  e.momentum = pn > 0.0 ? d / pn : d;
  e.max = std::max(e.attitude, e.momentum);
  return e;
}

RunResult run_once(const integrators::SchemeInfo& scheme, const system::AnyModel& model, const system::State& initial,
                   const integrators::RunConfig& cfg) {
  RunResult r;
  r.final = initial;
  FinalStateObserver observer;
  try {
    r.stats = scheme.run(model, r.final, cfg, observer);
  } catch (const std::exception& e) {
    r.threw = true;
    r.stats.ok = false;
    r.stats.status = e.what();
  }
  return r;
}

integrators::RunConfig make_config(double t_end, std::optional<double> dt, std::optional<double> tol) {
  integrators::RunConfig cfg;
  cfg.t0 = 0.0;
  cfg.t_end = t_end;
  cfg.dt = dt.value_or(0.0);
  cfg.tol = tol.value_or(0.0);
  cfg.save_every = std::numeric_limits<std::int64_t>::max();  // observe the initial and the final state only
  return cfg;
}

double row_floor(double reference_error, double amplification, std::int64_t steps) {
  constexpr double unit_roundoff = 0x1p-53;
  return std::max(reference_error, 4.0 * amplification * unit_roundoff * static_cast<double>(steps));
}

Reference compute_reference(const system::Scene& scene, const system::AnyModel& model, double t_end,
                            const std::atomic<bool>* stop) {
  Reference ref;
  if (const auto* free = std::get_if<system::FreeBody>(&model)) {
    ref.kind = "exact";
    ref.scheme = "exact";
    const system::FreeBodyExactFlow flow(free->inertia, scene.initial);
    ref.state = flow.at(t_end);
    const ExactFloor floor = exact_conditioning_floor(free->inertia, scene.initial, ref.state, t_end);
    ref.estimated_error = floor.floor;
    ref.amplification = floor.amplification;
    ref.steps = 0;
    return ref;
  }
  const integrators::SchemeInfo* scheme = integrators::find_scheme(converged_reference_scheme);
  if (!scheme)
    throw RunError(std::string("work-precision: the reference scheme ") + converged_reference_scheme +
                   " is not registered");
  std::string last_failure;
  const auto config = [&](double tol) {
    integrators::RunConfig cfg = make_config(t_end, std::nullopt, tol);
    cfg.stop = stop;
    return cfg;
  };
  for (const double tol : {1e-14, 1e-13, 1e-12}) {
    const RunResult fine = run_once(*scheme, model, scene.initial, config(tol));
    if (fine.stats.interrupted) throw ReferenceInterrupted{};
    if (!fine.stats.ok) {
      last_failure = "at tol " + format_general(tol, 3) + ": " + fine.stats.status;
      continue;
    }
    const RunResult coarse = run_once(*scheme, model, scene.initial, config(10.0 * tol));
    if (coarse.stats.interrupted) throw ReferenceInterrupted{};
    if (!coarse.stats.ok) {
      last_failure = "at tol " + format_general(10.0 * tol, 3) + ": " + coarse.stats.status;
      continue;
    }
    ref.kind = "converged";
    ref.scheme = scheme->name;
    ref.tol = tol;
    ref.comparison_tol = 10.0 * tol;
    ref.estimated_error = global_error(coarse.final, fine.final).max;
    ref.steps = fine.stats.steps;
    ref.cpu_seconds = fine.stats.cpu_seconds;
    ref.state = fine.final;
    if (!std::isfinite(ref.estimated_error)) {
      last_failure = "non-finite error estimate";
      continue;
    }
    return ref;
  }
  throw RunError("work-precision: no converged reference for " + scene.file + " (" + converged_reference_scheme + " " +
                 last_failure + ")");
}

}  // namespace lgi::experiments

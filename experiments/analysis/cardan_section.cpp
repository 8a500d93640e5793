#include "experiments/analysis/cardan_section.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "experiments/analysis/cardan_equilibria.hpp"
#include "experiments/analysis/seeded_random.hpp"
#include "experiments/errors/exit_status.hpp"
#include "integrators/registry/registry.hpp"
#include "integrators/core/torus_tangent_flow.hpp"
#include "integrators/ensemble/cardan_tangent_ensemble.hpp"

namespace lgi::experiments {
namespace {

using system::TorusState;
using std::numbers::pi;
constexpr std::uint64_t draw_stream = 0x5ec7104ULL, tangent_stream = 0x7a1e5cULL;

double factor(const system::CardanTop& top, const TorusState& x, int which) {
  return cardan_section_factor(top, x, which);
}
double section_value(const system::CardanTop& top, const TorusState& x) {
  return -std::sin(x.q(1)) * top.velocity(x)(1);
}

CardanCrossing crossing_at(const system::CardanTop& top, const TorusState& x, double t, int which, int direction) {
  return cardan_crossing_at(top, x, t, which, direction);
}

/// The section's two factors as the loop's event functions (integrators/core/events.hpp):
/// event 0 is q̇2 = 0, event 1 sin q2 = 0, both directions.
class SectionFactors final : public integrators::BasicEventFunctions<TorusState> {
 public:
  explicit SectionFactors(const system::CardanTop& top) : top_(top) {}
  int count() const override { return 2; }
  double value(int event, double /*t*/, const TorusState& x) const override { return factor(top_, x, event); }
  int direction(int /*event*/) const override { return 0; }

 private:
  const system::CardanTop& top_;
};

/// Keeps the orbit's errors and crossings from the loop's samples (one a
/// step) and located events. A crossing's direction is the sign of the change
/// of S over its step, known at the step's sample; the crossings of one step
/// are kept in time order. More than max_crossings set `stop`, which ends the
/// run after that step.
class SectionObserver final : public integrators::TorusObserver {
 public:
  SectionObserver(const system::CardanTop& top, const CardanOrbitRequest& r, CardanOrbit& o, std::atomic<bool>& stop)
      : top_(top), r_(r), o_(o), stop_(stop) {}

  void on_event(const integrators::BasicEventHit<TorusState>& hit) override { step_hits_.push_back(hit); }
  void observe(std::int64_t step, double /*t*/, const TorusState& x) override {
    if (r_.interrupt && r_.interrupt->load(std::memory_order_relaxed)) stop_.store(true, std::memory_order_relaxed);
    if (truncated_) return;  // the step after the last one kept (the loop reads the stop flag then)
    if (step == 0) {
      H0_ = top_.energy(x), p10_ = x.p(0);
      // Errors relative to max(|H0|, T0), T0 the kinetic energy: H0 may be 0 on a level set.
      energy_scale_ = std::max({std::abs(H0_), 0.5 * x.p.dot(top_.velocity(x)), 1e-300});
    } else {
      o_.max_energy_error = std::max(o_.max_energy_error, std::abs(top_.energy(x) - H0_) / energy_scale_);
      o_.max_momentum_error =
          std::max(o_.max_momentum_error, std::abs(x.p(0) - p10_) / std::max(std::abs(p10_), 1e-300));
      keep_crossings(x);
      if (truncated_) truncated_at_ = step;
    }
    last_ = x;
  }
  /// The state of the last step kept: not a failed step's, nor one after the crossings ran over.
  const TorusState& last() const { return last_; }
  bool truncated() const { return truncated_; }
  /// The step whose crossings ran over (the run itself takes one step more).
  std::int64_t truncated_at() const { return truncated_at_; }

 private:
  void keep_crossings(const TorusState& x) {
    const int direction = section_value(top_, x) > section_value(top_, last_) ? 1 : -1;
    std::sort(step_hits_.begin(), step_hits_.end(), [](const auto& a, const auto& b) { return a.t < b.t; });
    for (const auto& hit : step_hits_) {
      if (static_cast<std::int64_t>(o_.crossings.size()) >= r_.max_crossings) {
        truncated_ = true;
        stop_.store(true, std::memory_order_relaxed);
        break;
      }
      o_.crossings.push_back(crossing_at(top_, hit.state, hit.t, hit.event, direction));
    }
    step_hits_.clear();
  }

  const system::CardanTop& top_;
  const CardanOrbitRequest& r_;
  CardanOrbit& o_;
  std::atomic<bool>& stop_;
  std::vector<integrators::BasicEventHit<TorusState>> step_hits_;
  TorusState last_{};
  double H0_ = 0.0, p10_ = 0.0, energy_scale_ = 1.0;
  std::int64_t truncated_at_ = 0;
  bool truncated_ = false;
};

/// The orbit on the one time loop (integrators/core/stepper_loop.hpp), its
/// crossings located by the loop's events on the scheme's step map.
void integrate_orbit(const system::CardanTop& top, const CardanOrbitRequest& r, CardanOrbit& o) {
  if (std::string why = integrators::fixed_step_grid_problem(0.0, r.t_end, r.dt); !why.empty()) {
    o.status = 1;  // never a finished orbit with no steps
    o.reason = std::move(why);
    return;
  }
  const SectionFactors factors(top);
  std::atomic<bool> stop{false};
  SectionObserver observer(top, r, o, stop);
  integrators::TorusRunConfig cfg;
  cfg.t_end = r.t_end;
  cfg.dt = r.dt;
  cfg.cpu_clock = false;
  cfg.events = &factors;
  cfg.stop = &stop;
  TorusState x = o.initial;
  const integrators::RunStats stats = integrators::find_cardan_scheme(r.scheme)->run_cardan(top, x, cfg, observer);
  o.steps = stats.steps;
  if (observer.truncated()) {
    o.steps = observer.truncated_at();
    o.status = 3;
    o.reason = "more than " + std::to_string(r.max_crossings) + " crossings (--max-events)";
  } else if (!stats.ok) {
    o.status = 1;
    o.reason = stats.status;
  }
  o.final = observer.last();
}

/// S, the Schur complement of M₁₁ in M at q: the shape's kinetic energy at fixed p1 is ½ uᵀ S u.
Eigen::Matrix2d shape_inertia(const Mat3& M) {
  return M.block<2, 2>(1, 1) - M.block<2, 1>(1, 0) * M.block<1, 2>(0, 1) / M(0, 0);
}

/// The state at shape q (q1 = 0) with shape velocity u and p1 = l.
TorusState with_shape_velocity(const system::CardanTop& top, const Vec3& q, const Mat3& M, const Eigen::Vector2d& u,
                               double l) {
  const Vec3 qdot((l - M(0, 1) * u(0) - M(0, 2) * u(1)) / M(0, 0), u(0), u(1));
  TorusState x = top.from_rates(q, qdot);
  x.p(0) = l;  // = M₁· q̇ up to round-off; the level's value exactly
  return x;
}

}  // namespace

double cardan_section_factor(const system::CardanTop& top, const TorusState& x, int which) {
  return which == 0 ? top.velocity(x)(1) : std::sin(x.q(1));
}

CardanCrossing cardan_crossing_at(const system::CardanTop& top, const TorusState& x, double t, int which,
                                  int direction) {
  CardanCrossing c;
  c.t = t, c.x = x, c.direction = direction;
  const Vec3 v = top.velocity(x);
  c.x_coord = wrap_angle_positive(x.q(2));
  if (which == 0) {
    c.piece = v(2) >= 0.0 ? 1 : -1;
    c.y_coord = wrap_angle_positive(x.q(1));
  } else {
    c.piece = std::cos(x.q(1)) > 0.0 ? 2 : 3;
    c.y_coord = std::atan2(v(2), v(1));
  }
  return c;
}

bool cardan_section_state(const system::CardanTop& top, double l, double h, double x, double y, int piece,
                          TorusState& state) {
  const bool torus = piece == 1 || piece == -1;
  const Vec3 q(0.0, torus ? y : (piece == 2 ? 0.0 : pi), x);
  const Mat3 M = top.mass_matrix(q);
  const Eigen::Matrix2d S = shape_inertia(M);
  const Eigen::Vector2d dir = torus ? Eigen::Vector2d(0.0, piece) : Eigen::Vector2d(std::cos(y), std::sin(y));
  const double surplus = h - cardan_amended_potential(top, l, q(1), q(2)), quad = dir.dot(S * dir);
  if (!(surplus >= 0.0) || !(quad > 0.0)) return false;
  state = with_shape_velocity(top, q, M, std::sqrt(2.0 * surplus / quad) * dir, l);
  return state.p.allFinite();
}

void check_cardan_section_scheme(const std::string& name) {
  if (name != "cardan-rk4" && name != "cardan-midpoint" && name != "cardan-dg")
    throw UsageError("--scheme: " + name + ": lgi poincare on a Cardan top takes a fixed-step T^3 scheme: "
                     "cardan-rk4, cardan-midpoint or cardan-dg");
}

bool draw_cardan_level_point(const system::CardanTop& top, double l, double h, std::uint64_t seed,
                             std::int64_t index, TorusState& x) {
  CounterRng rng(seed, index, draw_stream);
  for (int attempt = 0; attempt < 100000; ++attempt) {
    const double q2 = -pi + 2.0 * pi * rng.uniform(), q3 = 2.0 * pi * rng.uniform(), phi = 2.0 * pi * rng.uniform();
    const double surplus = h - cardan_amended_potential(top, l, q2, q3);
    if (!(surplus >= 0.0)) continue;
    const Vec3 q(0.0, q2, q3);
    const Mat3 M = top.mass_matrix(q);
    const Eigen::LLT<Eigen::Matrix2d> llt(shape_inertia(M));
    if (llt.info() != Eigen::Success) continue;  // M singular here (gimbal lock without ring inertia)
    const Eigen::Vector2d u =
        std::sqrt(2.0 * surplus) * llt.matrixU().solve(Eigen::Vector2d(std::cos(phi), std::sin(phi)));
    x = with_shape_velocity(top, q, M, u, l);
    return true;
  }
  return false;
}

namespace {

/// The orbit's first tangent vector: a draw of the unit cube from (seed, index).
system::Vec6 orbit_tangent(std::uint64_t seed, std::int64_t index) {
  CounterRng rng(seed, index, tangent_stream);
  system::Vec6 v;
  for (int k = 0; k < 6; ++k) v(k) = 2.0 * rng.uniform() - 1.0;
  return v;
}

}  // namespace

void cardan_orbit_indicators(const system::CardanTop& top, const TorusState& x0, double t_end, double dt,
                             std::uint64_t seed, std::int64_t index, double& lyapunov, double& megno,
                             const std::atomic<bool>* stop) {
  system::Vec6 x = system::stack(x0);
  const auto ind = integrators::ensemble::scalar_cardan_chaos_indicators(integrators::ensemble::cardan_lane_model(top),
                                                                         x, orbit_tangent(seed, index), t_end, dt, stop);
  lyapunov = ind.lyapunov, megno = ind.megno;
}

void cardan_orbit_indicators(const system::CardanTop& top, std::span<const TorusState> x0, double t_end, double dt,
                             std::uint64_t seed, std::span<const std::int64_t> index,
                             std::optional<integrators::ensemble::Isa> isa, std::span<double> lyapunov,
                             std::span<double> megno, const std::atomic<bool>* stop) {
  std::optional<integrators::ensemble::CardanTangentEnsemble> e;
  if (isa && x0.size() > 1) e = integrators::ensemble::CardanTangentEnsemble::make(top, *isa);  // one orbit: the scalar step
  if (!e) {
    for (std::size_t k = 0; k < x0.size(); ++k)
      cardan_orbit_indicators(top, x0[k], t_end, dt, seed, index[k], lyapunov[k], megno[k], stop);
    return;
  }
  const auto width = static_cast<std::size_t>(e->lanes());
  for (std::size_t first = 0; first < x0.size(); first += width) {
    const std::size_t n = std::min(width, x0.size() - first);
    for (std::size_t l = 0; l < n; ++l)
      e->set_lane(static_cast<int>(l), system::stack(x0[first + l]), orbit_tangent(seed, index[first + l]));
    integrators::ChaosIndicators r[integrators::ensemble::max_lanes];
    e->chaos_indicators(0.0, t_end, dt, stop, {r, n});
    for (std::size_t l = 0; l < n; ++l) lyapunov[first + l] = r[l].lyapunov, megno[first + l] = r[l].megno;
  }
}

CardanOrbit cardan_orbit(const system::CardanTop& top, const TorusState& x0, const CardanOrbitRequest& r,
                         std::int64_t index) {
  CardanOrbit o;
  o.initial = x0;
  const double cpu0 = integrators::detail::cpu_now();
  integrate_orbit(top, r, o);
  if (r.indicators) cardan_orbit_indicators(top, x0, r.t_end, r.dt, r.seed, index, o.lyapunov, o.megno, r.interrupt);
  o.cpu_seconds = integrators::detail::cpu_now() - cpu0;
  return o;
}

}  // namespace lgi::experiments

#pragma once
// Events: crossings of surfaces g_i(t, x) = 0, found by the stepper loop
// (stepper_loop.hpp, RunConfig::events) after every accepted step.
//
// Detection. With g0 = g_i(t0, x0) before the step and g1 = g_i(t1, x1)
// after it, a rising crossing is g0 < 0 ≤ g1 and a falling one g0 > 0 ≥ g1
// (a zero at a step point is counted once, in the step that reaches it).
//
// Location. The crossing is a root of θ ↦ g_i(t0 + θ, Φ_θ(x0)) on (0, h].
//  - On the step map (fixed-step schemes, the adaptive ones without dense
//    output, and RunConfig::event_location = step_map): Φ_θ is the scheme's
//    own step of size θ from x0, taken by a copy of the scheme as it was
//    before the step. The located state lies on a trajectory of the scheme,
//    and its error is the scheme's local error, below the run's global error.
//  - On the dense output (the RKMK pairs with an interpolant, by default):
//    Φ_θ is the step's continuous extension (rkmk_pair.hpp), of order 7 for
//    DOP853, 6, 8 and 9 for Verner's pairs, so the located state's error is
//    the interpolant's local error, O(h^(q+1)). Its extra stages are
//    evaluated once per step with a crossing; every iteration after that
//    costs no field evaluation (a location step costs a whole step). This is
//    how Hairer's DOP853 and OrdinaryDiffEq.jl's callbacks locate events.
// Root finding is the Illinois variant of regula falsi (M. Dowell and
// P. Jarratt, "A modified regula falsi method for computing the root of an
// equation", BIT 11 (1971) 168–174): superlinear, and the bracket never
// stalls on one side. It ends when g is exactly zero, or when the bracket is
// at most 4 units in the last place of t (round-off in time); at most
// 100 iterations. The reported crossing is the bracket end with the smaller
// |g|.
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "integrators/core/scheme_interface.hpp"
#include "integrators/core/state_space.hpp"

namespace lgi::integrators {

/// The surfaces a run on states S watches (state_space.hpp). Evaluated once
/// per accepted step and per root-finding iteration, never inside the stage loop.
template <class S>
class BasicEventFunctions {
 public:
  virtual ~BasicEventFunctions() = default;
  virtual int count() const = 0;
  /// g_i(t, x); the surface is g_i = 0.
  virtual double value(int event, double t, const S& x) const = 0;
  /// +1: rising crossings only, −1: falling only, 0: both.
  virtual int direction(int event) const = 0;
};

/// One located crossing.
template <class S>
struct BasicEventHit {
  int event = 0;         // which surface (EventFunctions index)
  int direction = 0;     // +1 rising, −1 falling
  std::int64_t step = 0; // the accepted step it lies in (1-based, as the loop's step numbers)
  double t = 0.0;
  S state{};
  int iterations = 0;    // root-finding iterations (steps of the scheme, or evaluations of its dense output)
  double residual = 0.0; // |g| at the reported crossing
};

using EventFunctions = BasicEventFunctions<State>;  // on SO(3) × ℝ³
using EventHit = BasicEventHit<State>;

/// The sign change of one event over a step: +1 rising, −1 falling, 0 none
/// (or not in the direction asked for).
inline int crossing_direction(double g0, double g1, int wanted) {
  int d = 0;
  if (g0 < 0.0 && g1 >= 0.0) d = 1;
  else if (g0 > 0.0 && g1 <= 0.0) d = -1;
  return (wanted == 0 || wanted == d) ? d : 0;
}

/// Locates the crossing of event `i` in the step [t0, t0 + h] (top of this
/// file). `advance(θ, x)` sets x to Φ_θ(x0), the scheme's step of size θ
/// from x0 or its dense output at t0 + θ, and returns whether it succeeded
/// (an implicit solve converged, the state is finite); g0 and g1
/// are the event's values at both ends and x1 the state at t0 + h. Returns
/// false if a step of the search failed (the hit then holds the bracket end
/// reached so far).
template <class S, class Advance>
bool locate_crossing(const BasicEventFunctions<S>& events, int i, double t0, double h, const S& x0, const S& x1,
                     double g0, double g1, Advance&& advance, BasicEventHit<S>& hit) {
  double a = 0.0, b = h, fa = g0, fb = g1;
  S xa = x0, xb = x1, xc;
  int side = 0;
  const double resolution =
      4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(t0), std::abs(t0 + h));
  bool ok = true;
  int it = 0;
  while (it < 100 && fb != 0.0 && fa != 0.0 && std::abs(b - a) > resolution) {
    ++it;
    double c = (a * fb - b * fa) / (fb - fa);
    // Stay strictly inside the bracket (regula falsi can land on an end in round-off).
    if (!(std::abs(c - a) > 0.0 && std::abs(b - c) > 0.0) || !((c - a) * (b - c) > 0.0)) c = 0.5 * (a + b);
    if (!advance(c, xc)) {
      ok = false;
      break;
    }
    const double fc = events.value(i, t0 + c, xc);
    if (!std::isfinite(fc)) {  // a search step that blew up: no crossing can be vouched for
      ok = false;
      break;
    }
    if ((fc < 0.0) == (fb < 0.0) && fc != 0.0) {  // c replaces b
      b = c, fb = fc, xb = xc;
      if (side == -1) fa *= 0.5;
      side = -1;
    } else {  // c replaces a (or is the root)
      a = c, fa = fc, xa = xc;
      if (side == 1) fb *= 0.5;
      side = 1;
    }
  }
  // fa and fb may have been halved by the Illinois rule; compare true values.
  const double ga = std::abs(events.value(i, t0 + a, xa)), gb = std::abs(events.value(i, t0 + b, xb));
  const bool take_a = ga < gb && a != 0.0;
  hit.t = t0 + (take_a ? a : b);
  hit.state = take_a ? xa : xb;
  hit.residual = take_a ? ga : gb;
  hit.iterations = it;
  return ok;
}

}  // namespace lgi::integrators

#pragma once
// The tangent (variational) flow of the Cardan top on T³ × ℝ³ and its chaos
// indicators (docs/cardan.md §9), the counterpart of
// integrators/core/tangent_flow.hpp on SO(3).
//
// T³ × ℝ³ is flat (the angles are carried on the universal cover), so the
// tangent vector v ∈ ℝ⁶ perturbs x = (q, p) to x + v and obeys
//   v̇ = Df(x) v,
// f the canonical field of integrators/system/cardan.hpp. Df(x) v is exact:
// the field evaluated in dual numbers at x + v·ε (integrators/system/dual.hpp,
// integrators/system/cardan_field.hpp), whose ε-part is Df(x) v to
// round-off, with no difference step (docs/cardan.md §9.3 measures what the
// former central difference, relative error ~1e-10, cost the indicators).
// One dual evaluation per stage and vector.
//
// One step integrates (x, v) ∈ ℝ¹² with the classical RK4 tableau (HNW I,
// §II.1). The indicators are those of integrators/core/tangent_flow.hpp
// (ChaosAccumulator): λ after Benettin et al. (1980), MEGNO ⟨Y⟩ after
// Cincotta & Simó (2000), with v renormalised to 1 after every step.
#include <cmath>

#include "integrators/system/cardan.hpp"
#include "integrators/system/cardan_field.hpp"
#include "integrators/system/dual.hpp"
#include "integrators/core/tangent_flow.hpp"

namespace lgi::integrators::torus {

/// Df(x) v, exactly: the ε-part of the field at the dual point x + v·ε.
inline system::Vec6 torus_tangent_rate(const system::CardanTop& top, const system::Vec6& x, const system::Vec6& v) {
  using system::Dual;
  const system::cardan_detail::Vec3T<Dual> q(Dual(x[0], v[0]), Dual(x[1], v[1]), Dual(x[2], v[2]));
  const system::cardan_detail::Vec3T<Dual> p(Dual(x[3], v[3]), Dual(x[4], v[4]), Dual(x[5], v[5]));
  const system::cardan_detail::Vec6T<Dual> f = system::cardan_detail::field(top, q, p);
  system::Vec6 r;
  for (int k = 0; k < 6; ++k) r[k] = f[k].b;
  return r;
}

/// Df(x) V for six tangent vectors, the columns of V, each as above.
inline system::Mat6 torus_tangent_rate(const system::CardanTop& top, const system::Vec6& x, const system::Mat6& V) {
  system::Mat6 r;
  for (int k = 0; k < 6; ++k) r.col(k) = torus_tangent_rate(top, x, system::Vec6(V.col(k)));
  return r;
}

/// One RK4 step of (x, v) of size h; v is one tangent vector (Vec6) or six
/// (Mat6, the Lyapunov spectrum and GALI), advanced alike.
template <class Tangent>
void torus_tangent_step(const system::CardanTop& top, system::Vec6& x, Tangent& v, double h) {
  constexpr double a[4] = {0.0, 0.5, 0.5, 1.0};
  constexpr double b[4] = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
  system::Vec6 K = system::Vec6::Zero(), dx = system::Vec6::Zero();
  Tangent W = Tangent::Zero(), dv = Tangent::Zero();
  for (int i = 0; i < 4; ++i) {
    const system::Vec6 xi = x + (h * a[i]) * K;
    const Tangent vi = v + (h * a[i]) * W;
    K = top.field(system::unstack(xi));
    W = torus_tangent_rate(top, xi, vi);
    dx += (h * b[i]) * K;
    dv += (h * b[i]) * W;
  }
  x += dx;
  v += dv;
}

/// Integrates (x, v) over [0, t_end] with steps dt (the last one shortened)
/// and returns λ and ⟨Y⟩; NaN where the state or the tangent blew up, or
/// where a set `stop` flag ended the run (read every 256 steps).
inline ChaosIndicators torus_chaos_indicators(const system::CardanTop& top, system::TorusState& s,
                                              system::Vec6 v, double t_end, double dt,
                                              const std::atomic<bool>* stop = nullptr) {
  system::Vec6 x = system::stack(s);
  const ChaosIndicators out = accumulate_chaos_indicators(
      [&](double, double h, system::Vec6& w) { torus_tangent_step(top, x, w, h); }, [&] { return x.allFinite(); }, v,
      0.0, t_end, dt, stop);
  if (out.ok) s = system::unstack(x);
  return out;
}

}  // namespace lgi::integrators::torus

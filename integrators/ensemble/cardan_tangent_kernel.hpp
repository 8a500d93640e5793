#pragma once
// The Cardan top's tangent flow (integrators/core/torus_tangent_flow.hpp)
// written once for a lane number T, double or Lanes<Batch, K>
// (docs/ensemble.md, "Cardan tangent flows"): one classical RK4 step
// (HNW I, §II.1) of the state x = (q, p) ∈ T³ × ℝ³ and of NV tangent vectors
// v ∈ ℝ⁶. The scalar step (scalar_cardan_tangent_step,
// cardan_tangent_ensemble.cpp) is this template on double, so every lane is
// the scalar step bit for bit by construction; tests/test_ensemble_cardan.cpp
// checks it, and the field against CardanTop::field to round-off.
//
// Each stage evaluates the canonical field once, on the dual point
// x_i + Σ_k v_{i,k} ε_k (lane_dual.hpp): its value part is the stage rate
// of the state, its N derivative parts the stage rates Df(x_i) v_{i,k}.
// The field (docs/cardan.md eqs. (2)–(7)) is written out, not as Eigen
// products, so that its operations and their order are fixed:
//   E(q) = [E_a, E_b, e3], E_a = (s2 s3, s2 c3, c2), E_b = (c3, −s3, 0),
//   M = Eᵀ J E + diag-terms of the rings:  M00 += B_i s2² + C_i c2² + C_o,  M11 += A_i,
//   v = M⁻¹ p by the adjugate (M symmetric),  Ω = E v,  L = J Ω,
//   ½ vᵀ ∂M/∂q2 v = v1 L·(c2 s3, c2 c3, −s2) + (B_i − C_i) s2 c2 v1²,
//   ½ vᵀ ∂M/∂q3 v = L·(∂E/∂q3 v) = L1 Ω2 − L2 Ω1   (∂E/∂q3 v = (Ω2, −Ω1, 0)),
//   ∂V/∂q = (g1·(e3 × w), g2·(e1 × u), g3·(e3 × g m χ)),  g1 = Rz(q1)ᵀγ, g2 = Rx(q2)ᵀ g1, g3 = Rz(q3)ᵀ g2,
//   u = Rz(q3) g m χ + g m_i c_i,  w = Rx(q2) u + g m_o c_o   (components numbered from 1),
//   ṗ = ½ vᵀ (∂M/∂q) v − ∂V/∂q,  q̇ = v.
// J is taken symmetric (an inertia tensor). cos and sin of the angles come
// from lane_sincos.hpp, the same operations on double and in lanes (libm's
// lane by lane left the lanes at 2.6 × on AVX-512): q2 and q3 at every
// stage, q1 only where the frame is tilted and gravity acts.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "integrators/ensemble/cardan_tangent_block.hpp"
#include "integrators/ensemble/chaos_lanes_loop.hpp"
#include "integrators/ensemble/lane_dual.hpp"
#include "integrators/core/flatten_policy.hpp"

namespace lgi::integrators::ensemble {

namespace cardan_detail {

/// ∂V/∂q (top of this file) at the angles whose cos and sin are given.
template <class T, std::size_t NV>
inline void potential_gradient(const CardanLaneModel& m, const DualN<T, NV>& q1, const DualN<T, NV>& c2,
                               const DualN<T, NV>& s2, const DualN<T, NV>& c3, const DualN<T, NV>& s3,
                               DualN<T, NV> (&dV)[3]) {
  using N = DualN<T, NV>;
  const double(&mc)[3] = m.body;
  const N u0 = (mc[0] * c3 - mc[1] * s3) + m.inner_moment[0];
  const N u1 = (mc[0] * s3 + mc[1] * c3) + m.inner_moment[1];
  const double u2 = mc[2] + m.inner_moment[2];
  const N w0 = u0 + m.outer_moment[0];
  const N w1 = (c2 * u1 - u2 * s2) + m.outer_moment[1];
  N g1[3];
  if (m.tilted) {
    N c1, s1;
    cos_sin(q1, c1, s1);
    g1[0] = m.gamma[0] * c1 + m.gamma[1] * s1;
    g1[1] = m.gamma[1] * c1 - m.gamma[0] * s1;
  } else {
    g1[0] = constant_dual<T, NV>(T(m.gamma[0]));
    g1[1] = constant_dual<T, NV>(T(m.gamma[1]));
  }
  const double g12 = m.gamma[2];
  const N g21 = c2 * g1[1] + g12 * s2;
  const N g22 = g12 * c2 - s2 * g1[1];
  const N g30 = c3 * g1[0] + s3 * g21;
  const N g31 = c3 * g21 - s3 * g1[0];
  dV[0] = g1[1] * w0 - g1[0] * w1;
  dV[1] = g22 * u1 - u2 * g21;
  dV[2] = mc[0] * g31 - mc[1] * g30;
}

/// The canonical field f(y) (top of this file), value and derivative parts.
template <class T, std::size_t NV>
inline void field(const CardanLaneModel& m, const DualN<T, NV> (&y)[6], DualN<T, NV> (&f)[6]) {
  using N = DualN<T, NV>;
  const double(&J)[3][3] = m.J;
  N c2, s2, c3, s3;
  cos_sin(y[1], c2, s2);
  cos_sin(y[2], c3, s3);
  const N ea[3] = {s2 * s3, s2 * c3, c2};
  N jea[3], jeb[3];
  for (int i = 0; i < 3; ++i) {
    jea[i] = (J[i][0] * ea[0] + J[i][1] * ea[1]) + J[i][2] * ea[2];
    jeb[i] = J[i][0] * c3 - J[i][1] * s3;
  }
  const N rings = (m.inner[1] * (s2 * s2) + m.inner[2] * (c2 * c2)) + m.outer;
  const N m00 = ((ea[0] * jea[0] + ea[1] * jea[1]) + ea[2] * jea[2]) + rings;
  const N m01 = (ea[0] * jeb[0] + ea[1] * jeb[1]) + ea[2] * jeb[2];
  const N m02 = (J[0][2] * ea[0] + J[1][2] * ea[1]) + J[2][2] * ea[2];
  const N m11 = (c3 * jeb[0] - s3 * jeb[1]) + m.inner[0];
  const N m12 = J[0][2] * c3 - J[1][2] * s3;
  const double m22 = J[2][2];
  // The adjugate of the symmetric M and its determinant.
  const N a00 = m22 * m11 - m12 * m12, a01 = m02 * m12 - m22 * m01, a02 = m01 * m12 - m02 * m11;
  const N a11 = m22 * m00 - m02 * m02, a12 = m01 * m02 - m00 * m12, a22 = m00 * m11 - m01 * m01;
  const N r = reciprocal((m00 * a00 + m01 * a01) + m02 * a02);
  const N& p0 = y[3];
  const N& p1 = y[4];
  const N& p2 = y[5];
  const N v0 = ((a00 * p0 + a01 * p1) + a02 * p2) * r;
  const N v1 = ((a01 * p0 + a11 * p1) + a12 * p2) * r;
  const N v2 = ((a02 * p0 + a12 * p1) + a22 * p2) * r;
  const N om[3] = {ea[0] * v0 + c3 * v1, ea[1] * v0 - s3 * v1, c2 * v0 + v2};
  N L[3];
  for (int i = 0; i < 3; ++i) L[i] = (J[i][0] * om[0] + J[i][1] * om[1]) + J[i][2] * om[2];
  const N ring = (m.inner[1] - m.inner[2]) * ((s2 * c2) * (v0 * v0));
  const N kinetic1 = v0 * (((c2 * s3) * L[0] + (c2 * c3) * L[1]) - s2 * L[2]) + ring;
  const N kinetic2 = L[0] * om[1] - L[1] * om[0];
  f[0] = v0, f[1] = v1, f[2] = v2;
  if (m.potential) {
    N dV[3];
    potential_gradient(m, y[0], c2, s2, c3, s3, dV);
    f[3] = -dV[0], f[4] = kinetic1 - dV[1], f[5] = kinetic2 - dV[2];
  } else {
    f[3] = constant_dual<T, NV>(T(0.0)), f[4] = kinetic1, f[5] = kinetic2;
  }
}

}  // namespace cardan_detail

/// One RK4 step of x and the vectors v from t to t + h (the field is autonomous):
/// y_i = (x + h a_i K_{i−1}, v + h a_i W_{i−1}), (K_i, W_i) = f(y_i),
/// x' = x + Σ h b_i K_i, v' = v + Σ h b_i W_i, as torus_tangent_step.
template <std::size_t NV, class T>
inline void cardan_tangent_rk_step(const CardanLaneModel& m, T (&x)[6], T (&v)[NV][6], double h) {
  using N = DualN<T, NV>;
  constexpr double a[4] = {0.0, 0.5, 0.5, 1.0};
  constexpr double b[4] = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
  N f[6];
  T dx[6];
  T dv[NV][6];
  for (int i = 0; i < 4; ++i) {
    N y[6];
    const double ha = h * a[i], hb = h * b[i];
    for (int c = 0; c < 6; ++c) {
      if (i == 0) {
        y[c].a = x[c];
        for (std::size_t k = 0; k < NV; ++k) y[c].b[k] = v[k][c];
      } else {
        y[c].a = x[c] + ha * f[c].a;
        for (std::size_t k = 0; k < NV; ++k) y[c].b[k] = v[k][c] + ha * f[c].b[k];
      }
    }
    cardan_detail::field(m, y, f);
    for (int c = 0; c < 6; ++c) {
      if (i == 0) {
        dx[c] = hb * f[c].a;
        for (std::size_t k = 0; k < NV; ++k) dv[k][c] = hb * f[c].b[k];
      } else {
        dx[c] = dx[c] + hb * f[c].a;
        for (std::size_t k = 0; k < NV; ++k) dv[k][c] = dv[k][c] + hb * f[c].b[k];
      }
    }
  }
  for (int c = 0; c < 6; ++c) {
    x[c] = x[c] + dx[c];
    for (std::size_t k = 0; k < NV; ++k) v[k][c] = v[k][c] + dv[k][c];
  }
}

namespace cardan_detail {

template <class T, std::size_t NV>
inline void load_block(const TangentBlock& block, T (&x)[6], T (&v)[NV][6]) {
  using B = typename T::batch_type;
  for (int c = 0; c < 6; ++c) {
    x[c] = load<B, T::batches>(block.row[c]);
    for (std::size_t k = 0; k < NV; ++k) v[k][c] = load<B, T::batches>(block.row[tangent_row(static_cast<int>(k), c)]);
  }
}
template <class T, std::size_t NV>
inline void store_block(const T (&x)[6], const T (&v)[NV][6], TangentBlock& block) {
  for (int c = 0; c < 6; ++c) {
    store(x[c], block.row[c]);
    for (std::size_t k = 0; k < NV; ++k) store(v[k][c], block.row[tangent_row(static_cast<int>(k), c)]);
  }
}

/// |v| as Eigen 3.4 sums a Vec6's squares with SSE2 (tangent_kernel.hpp, eigen_norm6).
template <class T>
inline T norm6(const T (&v)[6]) {
  const T s0 = v[0] * v[0], s1 = v[1] * v[1], s2 = v[2] * v[2];
  const T s3 = v[3] * v[3], s4 = v[4] * v[4], s5 = v[5] * v[5];
  return sqrt((s0 + (s2 + s4)) + (s1 + (s3 + s5)));
}

}  // namespace cardan_detail

/// cardan_tangent_rk_step on the lanes of a TangentBlock (CardanStepKernel).
template <std::size_t NV, class T>
inline void cardan_block_step(const CardanLaneModel& m, TangentBlock& block, double h) {
  T x[6];
  T v[NV][6];
  cardan_detail::load_block(block, x, v);
  cardan_tangent_rk_step<NV>(m, x, v, h);
  cardan_detail::store_block(x, v, block);
}

/// The chaos indicators' loop (chaos_lanes_loop.hpp) on the Cardan step; a
/// lane stops where |v| is not finite and positive or x is not finite
/// (torus_chaos_indicators' test).
template <class T>
inline void cardan_chaos_block_run(const CardanLaneModel& m, TangentBlock& block, ChaosLanes& c, double t0,
                                   double t_end, double dt, std::int64_t max_steps) {
  T x[6];
  T v[1][6];
  cardan_detail::load_block(block, x, v);
  chaos_lanes_loop<T>(
      c, t0, t_end, dt, max_steps,
      [&](double, double h) {
        cardan_tangent_rk_step<1>(m, x, v, h);
        T z = x[0] - x[0];
        for (int i = 1; i < 6; ++i) z = z + (x[i] - x[i]);
        return LaneStepNorm<T>{cardan_detail::norm6(v[0]), z};
      },
      [&](const T& norm) {
        for (int i = 0; i < 6; ++i) v[0][i] = v[0][i] / norm;
      });
  cardan_detail::store_block(x, v, block);
}

/// The kernels of one lane type (CardanTangentKernelSet), flattened as kernel_set.hpp's.
template <std::size_t NV, class T>
LGI_FLATTEN inline void cardan_block_step_flattened(const CardanLaneModel& m, TangentBlock& block, double h) {
  cardan_block_step<NV, T>(m, block, h);
}
template <class T>
LGI_FLATTEN inline void cardan_chaos_block_run_flattened(const CardanLaneModel& m, TangentBlock& block,
                                                         ChaosLanes& c, double t0, double t_end, double dt,
                                                         std::int64_t max_steps) {
  cardan_chaos_block_run<T>(m, block, c, t0, t_end, dt, max_steps);
}

template <class LaneType>
CardanTangentKernelSet cardan_tangent_kernel_set() {
  CardanTangentKernelSet set;
  set.lanes = LaneType::size;
  if constexpr (LaneType::batch_type::size >= 4) {
    set.step_one = &cardan_block_step_flattened<1, LaneType>;
    set.step_six = &cardan_block_step_flattened<6, LaneType>;
    set.chaos = &cardan_chaos_block_run_flattened<LaneType>;
  } else {
    set.step_one = &cardan_block_step<1, LaneType>;
    set.step_six = &cardan_block_step<6, LaneType>;
    set.chaos = &cardan_chaos_block_run<LaneType>;
  }
  return set;
}

}  // namespace lgi::integrators::ensemble

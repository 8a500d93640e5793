#pragma once
// The tangent flow of integrators/core/tangent_flow.hpp for lane numbers: one
// RKMK4 step of the state (R, Π) and of NV tangent vectors v = (ξ, δΠ), on
// T = double or Lanes<Batch, K> (docs/ensemble.md, "Tangent flows in lanes").
// The scalar step of the models with a kernel (scalar_tangent_step,
// tangent_ensemble.cpp) is this template on double, so every lane is bit for
// bit the scalar step by construction; tests/test_ensemble_tangent.cpp checks
// it, and that the state part is Rkmk4::step's.
//
// State: rkmk_kernel.hpp's detail::stage on the classical RK4 tableau, the
// one function rkmk4's lanes use, which hands each stage's Π_i, Ω_i and
// attitude rows to the tangent part (detail::StageView). Tangent: with the
// stage state Y_i (Ω_i = J⁻¹Π_i, R_i) and V_i = v + h (a_i W_{i−1}), the
// stage rate W_i = A(Y_i) V_i is
//   ξ̇  = ξ × Ω + u,                       u = J⁻¹δΠ,
//   δΠ̇ = Π × u + δΠ × Ω + δτ,
//   δτ = (Γ × ξ) × m g χ  [gravity] + (B_b × ξ) × (−μ)  [magnetic dipole]
// (Γ = Rᵀe3, B_b = RᵀB: under R → R exp(ξ̂) they move by Γ × ξ, B_b × ξ; the
// harmonic drive does not depend on the state). This is A of tangent_flow.hpp
// applied as directional derivatives, without forming the 6 × 6 matrix.
// v' = v + h ((b1 W1 + b2 W2) + b3 W3) + b4 W4.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "integrators/ensemble/ensemble_model.hpp"
#include "integrators/ensemble/lane_so3.hpp"
#include "integrators/ensemble/rkmk_kernel.hpp"
#include "integrators/ensemble/tangent_block.hpp"
#include "integrators/core/flatten_policy.hpp"
#include "integrators/tableaus/runge_kutta.hpp"

namespace lgi::integrators::ensemble {

/// One tangent vector v = (ξ, δΠ).
template <class T>
struct Tangent6 {
  V3<T> xi, dPi;
};

namespace tangent_detail {

inline constexpr auto& rk4 = tableaus::classical_rk4;

/// What the tangent rates of a stage read of its attitude R_i: Γ = Rᵀe3 and B_b = RᵀB.
template <class T>
struct StageFrame {
  V3<T> gamma, field;
};

/// W = A(Y_i) V (top of this file).
template <class T>
inline Tangent6<T> tangent_rate(const EnsembleModel& model, const V3<T>& Pi_i, const V3<T>& Omega_i,
                                const StageFrame<T>& frame, const Tangent6<T>& v) {
  const V3<T> u = mat_vec(model.J_inv, v.dPi);
  Tangent6<T> w{add(cross(v.xi, Omega_i), u), add(cross(Pi_i, u), cross(v.dPi, Omega_i))};
  if (model.free_body) return w;
  if (model.gravity) {
    const V3<double> c{{model.mg_chi[0], model.mg_chi[1], model.mg_chi[2]}};
    w.dPi = add(w.dPi, cross(cross(frame.gamma, v.xi), c));
  }
  if (model.magnetic) {
    const double(&m)[3] = model.magnetic_minus_moment;
    w.dPi = add(w.dPi, cross(cross(frame.field, v.xi), V3<double>{{m[0], m[1], m[2]}}));
  }
  return w;
}

/// Stage I of the state (rkmk_kernel.hpp's detail::stage on RK4, the same
/// function) and of the NV vectors at that stage's Π_i, Ω_i and attitude:
/// w holds W_{I−1} on entry and W_I on return, sum Σ_{j≤I} b_j W_j.
template <std::size_t I, class T, std::size_t NV>
inline void stage(const EnsembleModel& model, const M3<T>& R, const V3<T>& Pi, const Tangent6<T> (&v)[NV],
                  double t, double h, V3<T>* k_algebra, V3<T>* k_momentum, Tangent6<T> (&w)[NV],
                  Tangent6<T> (&sum)[NV]) {
  detail::stage<rk4, I>(model, R, Pi, t, h, k_algebra, k_momentum, [&](const detail::StageView<T>& y) {
    StageFrame<T> frame{zero3<T>(), zero3<T>()};
    if (y.R_i) {
      const M3<T>& R_i = *y.R_i;
      if (model.gravity) frame.gamma = V3<T>{{R_i.m[2][0], R_i.m[2][1], R_i.m[2][2]}};
      if (model.magnetic) frame.field = transposed_mat_vec(R_i, model.magnetic_field);
    }
    constexpr double a = I == 0 ? 0.0 : rk4.a[I][I == 0 ? 0 : I - 1];  // RK4: a_ij = 0 but below the diagonal
    constexpr double b = rk4.b[I];
    for (std::size_t k = 0; k < NV; ++k) {
      Tangent6<T> vi = v[k];
      if constexpr (I > 0) {
        vi.xi = add(v[k].xi, scale(h, scale(a, w[k].xi)));
        vi.dPi = add(v[k].dPi, scale(h, scale(a, w[k].dPi)));
      }
      w[k] = tangent_rate(model, y.Pi_i, y.Omega_i, frame, vi);
      if constexpr (I == 0) {
        sum[k] = Tangent6<T>{scale(b, w[k].xi), scale(b, w[k].dPi)};
      } else {
        sum[k] = Tangent6<T>{add(sum[k].xi, scale(b, w[k].xi)), add(sum[k].dPi, scale(b, w[k].dPi))};
      }
    }
  });
}

}  // namespace tangent_detail

/// One RKMK4 step of (R, Π) and of the vectors v from t to t + h in every lane.
template <std::size_t NV, class T>
inline void tangent_rk_step(const EnsembleModel& model, M3<T>& R, V3<T>& Pi, Tangent6<T> (&v)[NV], double t,
                            double h) {
  V3<T> k_algebra[4];
  V3<T> k_momentum[4];
  Tangent6<T> w[NV];
  Tangent6<T> sum[NV];
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (tangent_detail::stage<I>(model, R, Pi, v, t, h, k_algebra, k_momentum, w, sum), ...);
  }(std::make_index_sequence<4>{});
  V3<T> wv = zero3<T>(), dPi = zero3<T>();
  for (std::size_t i = 0; i < 4; ++i) {
    wv = add(wv, scale(tangent_detail::rk4.b[i], k_algebra[i]));
    dPi = add(dPi, scale(tangent_detail::rk4.b[i], k_momentum[i]));
  }
  const V3<T> hw = scale(h, wv);
  R = times_exp(R, hw, map_coefficients(lie::exp_series::squared_norm(hw.v), true));
  Pi = add(Pi, scale(h, dPi));
  for (std::size_t k = 0; k < NV; ++k) {
    v[k].xi = add(v[k].xi, scale(h, sum[k].xi));
    v[k].dPi = add(v[k].dPi, scale(h, sum[k].dPi));
  }
}

/// |v| in the order Eigen 3.4 sums a Vec6's squares with SSE2 (three packets
/// of two, p0 + (p1 + p2), then the packet's two halves), as v.norm() in
/// accumulate_chaos_indicators.
template <class T>
inline T eigen_norm6(const Tangent6<T>& v) {
  const T s0 = v.xi.v[0] * v.xi.v[0], s1 = v.xi.v[1] * v.xi.v[1], s2 = v.xi.v[2] * v.xi.v[2];
  const T s3 = v.dPi.v[0] * v.dPi.v[0], s4 = v.dPi.v[1] * v.dPi.v[1], s5 = v.dPi.v[2] * v.dPi.v[2];
  return sqrt((s0 + (s2 + s4)) + (s1 + (s3 + s5)));
}

namespace tangent_detail {

template <class T>
inline T load_row(const TangentBlock& block, int row) {
  return load<typename T::batch_type, T::batches>(block.row[row]);
}
template <class T, std::size_t NV>
inline void load_block(const TangentBlock& block, M3<T>& R, V3<T>& Pi, Tangent6<T> (&v)[NV]) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) R.m[i][j] = load_row<T>(block, 3 * i + j);
    Pi.v[i] = load_row<T>(block, 9 + i);
  }
  for (std::size_t k = 0; k < NV; ++k)
    for (int i = 0; i < 3; ++i) {
      v[k].xi.v[i] = load_row<T>(block, tangent_row(static_cast<int>(k), i));
      v[k].dPi.v[i] = load_row<T>(block, tangent_row(static_cast<int>(k), 3 + i));
    }
}
template <class T, std::size_t NV>
inline void store_block(const M3<T>& R, const V3<T>& Pi, const Tangent6<T> (&v)[NV], TangentBlock& block) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) store(R.m[i][j], block.row[3 * i + j]);
    store(Pi.v[i], block.row[9 + i]);
  }
  for (std::size_t k = 0; k < NV; ++k)
    for (int i = 0; i < 3; ++i) {
      store(v[k].xi.v[i], block.row[tangent_row(static_cast<int>(k), i)]);
      store(v[k].dPi.v[i], block.row[tangent_row(static_cast<int>(k), 3 + i)]);
    }
}

}  // namespace tangent_detail

/// tangent_rk_step on the lanes of a TangentBlock (TangentStepKernel).
template <std::size_t NV, class T>
inline void tangent_block_step(const EnsembleModel& model, TangentBlock& block, double t, double h) {
  M3<T> R;
  V3<T> Pi;
  Tangent6<T> v[NV];
  tangent_detail::load_block(block, R, Pi, v);
  tangent_rk_step<NV>(model, R, Pi, v, t, h);
  tangent_detail::store_block(R, Pi, v, block);
}
/// Flattened for batches of 4 or more doubles, as rkmk_block_step_flattened.
template <std::size_t NV, class T>
LGI_FLATTEN inline void tangent_block_step_flattened(const EnsembleModel& model, TangentBlock& block, double t,
                                                     double h) {
  tangent_block_step<NV, T>(model, block, t, h);
}

}  // namespace lgi::integrators::ensemble

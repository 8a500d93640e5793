#pragma once
// The RKMK step (integrators/schemes/rkmk.hpp) for lane numbers: the same stages,
// the same operations in the same order, on T = double or Lanes<Batch, K>
// (docs/ensemble.md). rkmk.hpp states the scheme; this is its ensemble
// form, checked bit for bit against it (tests/test_ensemble.cpp):
//   w_i = h Σ_{j<i} a_ij k̃_j,  Π_i = Π_n + h Σ_{j<i} a_ij K_j,  Ω_i = J⁻¹Π_i,
//   k̃_i = dexp⁻¹_body(w_i) Ω_i (k̃_1 = Ω_1),  K_i = Π_i × Ω_i + τ(R_n exp(w_i), t_n + c_i h),
//   R_{n+1} = R_n exp(h Σ b_i k̃_i),  Π_{n+1} = Π_n + h Σ b_i K_i.
// The tableau's zeros a_ij are skipped as rkmk.hpp skips them (at compile
// time here); its weights b_i are not (nor are they there).
#include <cmath>
#include <cstddef>
#include <utility>

#include "integrators/ensemble/ensemble_model.hpp"
#include "integrators/ensemble/lane_block.hpp"
#include "integrators/ensemble/lane_so3.hpp"
#include "integrators/core/flatten_policy.hpp"

namespace lgi::integrators::ensemble {

/// The body torque of system::SceneModel at (R, t): gravity + (spring + (drive + magnetic)),
/// the scene model's fold, an undeclared term contributing +0 (the spring never has a kernel).
template <class T>
inline V3<T> scene_torque(const EnsembleModel& model, const M3<T>& R, double t) {
  const V3<T> zero = zero3<T>();
  V3<T> gravity = zero, drive = zero, magnetic = zero;
  if (model.gravity) {
    const V3<T> gamma{{R.m[2][0], R.m[2][1], R.m[2][2]}};  // Γ = Rᵀe3, row 2 of R
    gravity = cross(gamma, V3<double>{{model.mg_chi[0], model.mg_chi[1], model.mg_chi[2]}});
  }
  if (model.drive) {  // A sin(ω t + φ): the same in every lane
    const double s = std::sin(model.drive_frequency * t + model.drive_phase);
    for (int i = 0; i < 3; ++i) drive.v[i] = T(model.drive_amplitude[i] * s);
  }
  if (model.magnetic) {
    const V3<T> b = transposed_mat_vec(R, model.magnetic_field);  // B_b = Rᵀ B
    const double(&c)[3] = model.magnetic_minus_moment;
    magnetic = cross(b, V3<double>{{c[0], c[1], c[2]}});
  }
  V3<T> tau;
  for (int i = 0; i < 3; ++i) tau.v[i] = gravity.v[i] + (zero.v[i] + (drive.v[i] + magnetic.v[i]));
  return tau;
}

namespace detail {

/// w = Σ_{j<i, a_ij ≠ 0} a_ij k_j from w = 0, as rkmk.hpp accumulates it.
template <const auto& Tableau, std::size_t I, class T, std::size_t... J>
inline void stage_sums(const V3<T>* k_algebra, const V3<T>* k_momentum, V3<T>& w, V3<T>& dPi,
                       std::index_sequence<J...>) {
  auto term = [&]<std::size_t Jc>() {
    constexpr double a = Tableau.a[I][Jc];
    if constexpr (a != 0.0) {
      w = add(w, scale(a, k_algebra[Jc]));
      dPi = add(dPi, scale(a, k_momentum[Jc]));
    }
  };
  (term.template operator()<J>(), ...);
  (void)term;  // stage 0 sums nothing
}

/// What stage I computes besides its k̃_i and K_i, for a caller that steps
/// more than the state (tangent_kernel.hpp): Π_i, Ω_i = J⁻¹Π_i and the stage
/// attitude R_i = R_n exp(w_i), nullptr on a free body (never formed there);
/// with gravity alone only its row 2 (Γ = R_iᵀe3) holds values.
template <class T>
struct StageView {
  const V3<T>& Pi_i;
  const V3<T>& Omega_i;
  const M3<T>* R_i;
};

/// Stage I of the RKMK step (top of this file): writes k̃_I and K_I, then
/// calls on_stage(StageView) (a no-op for rkmk_step).
template <const auto& Tableau, std::size_t I, class T, class OnStage>
inline void stage(const EnsembleModel& model, const M3<T>& R, const V3<T>& Pi, double t, double h,
                  V3<T>* k_algebra, V3<T>* k_momentum, OnStage&& on_stage) {
  V3<T> w = zero3<T>(), dPi = zero3<T>();
  stage_sums<Tableau, I>(k_algebra, k_momentum, w, dPi, std::make_index_sequence<I>{});
  w = scale(h, w);
  const V3<T> Pi_i = add(Pi, scale(h, dPi));
  const V3<T> Omega_i = mat_vec(model.J_inv, Pi_i);
  Coefficients<T> m{T(0.0), T(0.0), T(0.0)};
  if constexpr (I == 0) {
    k_algebra[I] = Omega_i;
  } else {
    m = map_coefficients(lie::exp_series::squared_norm(w.v), !model.free_body);
    k_algebra[I] = dexpinv_body(w, Omega_i, m);
  }
  const V3<T> gyroscopic = cross(Pi_i, Omega_i);
  if (model.free_body) {
    k_momentum[I] = gyroscopic;
    on_stage(StageView<T>{Pi_i, Omega_i, nullptr});
    return;
  }
  constexpr double c = Tableau.c[I];
  const auto at = [&](const M3<T>& R_i) {
    k_momentum[I] = add(gyroscopic, scene_torque(model, R_i, t + c * h));
    on_stage(StageView<T>{Pi_i, Omega_i, &R_i});
  };
  if constexpr (I == 0) {
    at(R);
  } else if (model.magnetic) {
    at(times_exp(R, w, m));
  } else {  // only row 2 of R_i = R_n exp(w_i) is read (gravity): the others are not formed
    M3<T> R_i;
    times_exp_row(R, 2, w, m, R_i);
    at(R_i);
  }
}

/// stage() with nothing more to do.
struct NoStageView {
  template <class View>
  void operator()(const View&) const {}
};

template <const auto& Tableau, class T, std::size_t... I>
inline void rkmk_stages(const EnsembleModel& model, const M3<T>& R, const V3<T>& Pi, double t, double h,
                        V3<T>* k_algebra, V3<T>* k_momentum, std::index_sequence<I...>) {
  (stage<Tableau, I>(model, R, Pi, t, h, k_algebra, k_momentum, NoStageView{}), ...);
}

}  // namespace detail

/// One RKMK step of (R, Π) from t to t + h in every lane.
template <const auto& Tableau, class T>
inline void rkmk_step(const EnsembleModel& model, M3<T>& R, V3<T>& Pi, double t, double h) {
  constexpr std::size_t stages = std::remove_cvref_t<decltype(Tableau)>::stages;
  V3<T> k_algebra[stages];
  V3<T> k_momentum[stages];
  detail::rkmk_stages<Tableau>(model, R, Pi, t, h, k_algebra, k_momentum, std::make_index_sequence<stages>{});
  V3<T> w = zero3<T>(), dPi = zero3<T>();
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    auto term = [&]<std::size_t Ic>() {
      constexpr double b = Tableau.b[Ic];
      w = add(w, scale(b, k_algebra[Ic]));
      dPi = add(dPi, scale(b, k_momentum[Ic]));
    };
    (term.template operator()<I>(), ...);
  }(std::make_index_sequence<stages>{});
  const V3<T> hw = scale(h, w);
  R = times_exp(R, hw, map_coefficients(lie::exp_series::squared_norm(hw.v), true));
  Pi = add(Pi, scale(h, dPi));
}

/// rkmk_step on the lanes of a LaneBlock (T = Lanes<Batch, K>, T::size lanes);
/// whether every active lane is finite after it (StepKernel).
template <const auto& Tableau, class T>
inline bool rkmk_block_step(const EnsembleModel& model, LaneBlock& block, LaneMemory& memory, double t, double h) {
  M3<T> R;
  V3<T> Pi;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R.m[i][j] = load<typename T::batch_type, T::batches>(block.row[3 * i + j]);
  for (int i = 0; i < 3; ++i) Pi.v[i] = load<typename T::batch_type, T::batches>(block.row[9 + i]);
  rkmk_step<Tableau>(model, R, Pi, t, h);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) store(R.m[i][j], block.row[3 * i + j]);
  for (int i = 0; i < 3; ++i) store(Pi.v[i], block.row[9 + i]);
  const T zero(0.0);
  return active_lanes_clear<T>(block, memory, equal(zero, 0.0));
}

/// rkmk_block_step flattened, as dmv_pre_block_step: GCC keeps the stages and
/// the maps' coefficients out of line, their lane arrays passed through
/// memory. For batches of 4 or more doubles (AVX2, AVX-512: +35–55% lanes per
/// second on the free body, docs/performance.md §5); SSE2's batches of 2, in 16
/// registers, ran 5–15% slower flattened (kernel_set.hpp). Inlining changes no result.
template <const auto& Tableau, class T>
LGI_FLATTEN inline bool rkmk_block_step_flattened(const EnsembleModel& model, LaneBlock& block, LaneMemory& memory,
                                                  double t, double h) {
  return rkmk_block_step<Tableau, T>(model, block, memory, t, h);
}

}  // namespace lgi::integrators::ensemble

#pragma once
// The DMV step (dmv, lgvi and the preprocessed dmv-pre4 … dmv-pre10,
// moser_veselov.hpp, moser_veselov_preprocessed.hpp) on a free body with diagonal J, for lane numbers: the common step of a run, in
// which the predictor holds six steps of this length and its guess passes
// after one Newton correction (moser_veselov_diagonal.hpp,
// solve_cayley_parameter_predicted). Every other case (the first six steps,
// a step of another length, a guess that does not pass, a step the scheme
// would refuse) is left untouched and flagged (dmv_rows::stepped = 0), and
// the scalar scheme takes that lane's step from its state and memory
// (lane_fallback.hpp), so a lane is the scalar run bit for bit whatever
// happens in it. Operation for operation, the scalar path it repeats is:
//   turns_too_far: (h h) |J⁻¹ ∘ Π|² < π² (DiagonalInertia::turns_too_far);
//   the moments: x = h², css = 1 + x p(x), cdd = 0 + x q(x) by Horner
//     (horner_in_h2), μ = 1/Ĩ = css J⁻¹ + cdd, all > 0 (dmv and lgvi:
//     μ = 1/(the moments of J)), 2μ, d_i = 2 (μ_j − μ_k) and the Newton bound
//     c = (2μ₁ + 2μ₂) + 2μ₃ (DiagonalMoments);
//   the guess h (((6 u₀ − 15 u₁) + (20 u₂ − 15 u₃)) + (6 u₄ − u₅)), u_m = w_m/h_m
//     (CayleyPredictor; w = J f, the unknown of moser_veselov_diagonal.hpp);
//   a = h Π, ψ at the guess with f = μ ∘ w (DiagonalPsi), the Jacobian,
//     Cramer's rule, w = p − δ, accepted when (c |δ|²)² ≤ 1e-38 |w|² and |δ|²
//     is finite; f = μ ∘ w;
//   Π ← cay(2f)ᵀ Π, and R ← R cay(2f) (dmv, lgvi) or, for the preprocessed
//     schemes, q ← q ⊗ p (cayley_quaternion.hpp; R(q) is formed by
//     EnsembleStepper::get_lane), as compensated sums (apply_cayley_step);
//   the history shifted, (1/h) w first.
// tests/test_ensemble_dmv.cpp checks the lanes against the scalar schemes step by step.
#include <bit>
#include <cstdint>
#include <numbers>

#include "integrators/schemes/cayley_increment.hpp"
#include "integrators/schemes/cayley_quaternion_increment.hpp"
#include "integrators/core/compensated_sum.hpp"
#include "integrators/ensemble/ensemble_model.hpp"
#include "integrators/ensemble/lane_block.hpp"
#include "integrators/ensemble/lanes.hpp"
#include "integrators/core/flatten_policy.hpp"

namespace lgi::integrators::ensemble {

namespace dmv_detail {

/// Σ_{k<degree} c_k x^k by Horner from the lane rows c, times x, plus offset (horner_in_h2).
template <class T>
inline T horner_in_h2(const LaneMemory& memory, int first_row, int degree, double x, double offset) {
  using B = typename T::batch_type;
  T v(0.0);
  for (int k = degree - 1; k >= 0; --k) v = load<B, T::batches>(memory.row[first_row + k]) + x * v;
  return offset + x * v;
}

/// The inverse modified moments μ = 1/Ĩ at step h for every lane (css J⁻¹ + cdd
/// with css, cdd the lane's series in x = h², DmvPreprocessed::free_step; for
/// dmv and lgvi the inverse moments of J, DiagonalInertia), 2μ, d and the
/// Newton bound c (DiagonalMoments), and where μ > 0; from the table of
/// LaneMemory where it holds this h, else computed and entered. A hit gives
/// what the computation gives, so the lanes do not depend on the table.
template <class T>
inline auto moments_for(const EnsembleModel& model, LaneMemory& memory, double h, T (&mu)[3], T (&two_mu)[3],
                        T (&d)[3], T& bound) {
  using B = typename T::batch_type;
  constexpr int K = T::batches;
  const auto slot = static_cast<int>((std::bit_cast<std::uint64_t>(h) * 0x9E3779B97F4A7C15ull) >> 61);
  double(*rows)[max_lanes] = memory.row + dmv_rows::moments + dmv_rows::moment_rows * slot;
  if (memory.moments_h[slot] == h) {
    for (int i = 0; i < 3; ++i)
      mu[i] = load<B, K>(rows[i]), two_mu[i] = load<B, K>(rows[3 + i]), d[i] = load<B, K>(rows[6 + i]);
    bound = load<B, K>(rows[10]);
    return equal(load<B, K>(rows[9]), 1.0);
  }
  auto positive = equal(T(0.0), 0.0);  // dmv and lgvi: the moments of J, no test
  if (!model.preprocessed) {
    for (int i = 0; i < 3; ++i) mu[i] = 1.0 / T(model.moments[i]);
  } else {
    const double Jd[3] = {model.J_inv[0][0], model.J_inv[1][1], model.J_inv[2][2]};
    const double x = h * h;
    const T css = horner_in_h2<T>(memory, dmv_rows::css, model.series_degrees, x, 1.0);
    const T cdd = horner_in_h2<T>(memory, dmv_rows::cdd, model.series_degrees, x, 0.0);
    for (int i = 0; i < 3; ++i) {
      mu[i] = css * Jd[i] + cdd;
      positive = positive & greater(mu[i], 0.0);
    }
  }
  for (int i = 0; i < 3; ++i) two_mu[i] = 2.0 * mu[i];
  d[0] = 2.0 * (mu[1] - mu[2]), d[1] = 2.0 * (mu[2] - mu[0]), d[2] = 2.0 * (mu[0] - mu[1]);
  bound = (two_mu[0] + two_mu[1]) + two_mu[2];
  for (int i = 0; i < 3; ++i) store(mu[i], rows[i]), store(two_mu[i], rows[3 + i]), store(d[i], rows[6 + i]);
  store(select(positive, T(1.0), T(0.0)), rows[9]);
  store(bound, rows[10]);
  memory.moments_h[slot] = h;
  return positive;
}

/// Π ← Fᵀ Π with its carry (CayleyIncrement::momentum_increment, apply_cayley_step).
template <class T>
inline void rotate_momentum(const moser_veselov::CayleyIncrement<T>& F, T (&P)[3], T (&cP)[3]) {
  T dP[3];
  F.momentum_increment(P, dP);
  for (int j = 0; j < 3; ++j) add_compensated(P[j], dP[j], cP[j]);
}

/// R ← R F with its carry (apply_cayley_step): dmv and lgvi.
template <class T>
inline void rotate_matrix(const moser_veselov::CayleyIncrement<T>& F, T (&R)[9], T (&cR)[9]) {
  T cN[9], dR[9];
  for (int k = 0; k < 9; ++k) cN[k] = F.c * F.N[k];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) dR[3 * i + j] = (R[3 * i] * cN[j] + R[3 * i + 1] * cN[3 + j]) + R[3 * i + 2] * cN[6 + j];
  for (int k = 0; k < 9; ++k) add_compensated(R[k], dR[k], cR[k]);
}

/// q ← q ⊗ p with its carry (CayleyQuaternion::rotate): the preprocessed schemes.
template <class T>
inline void rotate_quaternion(const moser_veselov::CayleyIncrement<T>& F, const T (&f)[3], T (&q)[4], T (&cq)[4]) {
  T dq[4];
  moser_veselov::cayley_quaternion_increment(q, f, F.ff, dq);
  for (int i = 0; i < 4; ++i) add_compensated(q[i], dq[i], cq[i]);
}

/// The unknown w = J f from the predictor's guess p (one Newton correction on
/// ψ with f = μ ∘ w, DiagonalPsi and diagonal_jacobian), its Cayley parameter
/// f = μ ∘ w, and whether it passes.
template <class T>
inline auto predicted_parameter(const T (&mu)[3], const T (&two_mu)[3], const T (&d)[3], const T& bound,
                                const T (&a)[3], const T (&p)[3], T (&w)[3], T (&f)[3]) {
  const T q0 = mu[0] * p[0], q1 = mu[1] * p[1], q2 = mu[2] * p[2];
  const T ff = (q0 * q0 + q1 * q1) + q2 * q2;
  const T p01 = q0 * p[1], p10 = q1 * p[0], p02 = q0 * p[2], p20 = q2 * p[0], p12 = q1 * p[2], p21 = q2 * p[1];
  const T r0 = (2.0 * p[0] - a[0]) + (2.0 * (p12 - p21) - ff * a[0]);
  const T r1 = (2.0 * p[1] - a[1]) + (2.0 * (p20 - p02) - ff * a[1]);
  const T r2 = (2.0 * p[2] - a[2]) + (2.0 * (p01 - p10) - ff * a[2]);
  // ∂ψ/∂w at p (diagonal_jacobian), row-major, and its adjugate (Cramer3).
  const T g0 = two_mu[0] * q0, g1 = two_mu[1] * q1, g2 = two_mu[2] * q2;
  const T j[9] = {2.0 - a[0] * g0,        d[0] * p[2] - a[0] * g1, d[0] * p[1] - a[0] * g2,
                  d[1] * p[2] - a[1] * g0, 2.0 - a[1] * g1,        d[1] * p[0] - a[1] * g2,
                  d[2] * p[1] - a[2] * g0, d[2] * p[0] - a[2] * g1, 2.0 - a[2] * g2};
  const T adj0 = j[4] * j[8] - j[5] * j[7], adj3 = j[5] * j[6] - j[3] * j[8], adj6 = j[3] * j[7] - j[4] * j[6];
  const T det_inv = 1.0 / (j[0] * adj0 + j[1] * adj3 + j[2] * adj6);
  const T adj1 = j[2] * j[7] - j[1] * j[8], adj2 = j[1] * j[5] - j[2] * j[4];
  const T adj4 = j[0] * j[8] - j[2] * j[6], adj5 = j[2] * j[3] - j[0] * j[5];
  const T adj7 = j[1] * j[6] - j[0] * j[7], adj8 = j[0] * j[4] - j[1] * j[3];
  const T d0 = det_inv * (adj0 * r0 + adj1 * r1 + adj2 * r2);
  const T d1 = det_inv * (adj3 * r0 + adj4 * r1 + adj5 * r2);
  const T d2 = det_inv * (adj6 * r0 + adj7 * r1 + adj8 * r2);
  w[0] = p[0] - d0;
  w[1] = p[1] - d1;
  w[2] = p[2] - d2;
  for (int i = 0; i < 3; ++i) f[i] = mu[i] * w[i];
  const T step2 = (d0 * d0 + d1 * d1) + d2 * d2;
  const T error_bound = bound * step2;
  return less_equal(error_bound * error_bound, 1e-38 * ((w[0] * w[0] + w[1] * w[1]) + w[2] * w[2])) &
         equal(step2 - step2, 0.0);
}

}  // namespace dmv_detail

/// The step of the top of this file in every lane of a LaneBlock (T = Lanes<Batch, K>);
/// whether every active lane was stepped here and is finite (StepKernel).
/// Flattened: GCC kept the compensated sums, the Cayley update, the solve and
/// the moments' lookup out of line, with every lane array passed through
/// memory (callgrind of `ensemble/free_body_hlw/dmv-pre10/avx2`: 19.1 million
/// instructions in this function and those calls, 16.3 million flattened;
/// inlining changes no result, flatten_policy.hpp).
template <class T>
LGI_FLATTEN inline bool dmv_pre_block_step(const EnsembleModel& model, LaneBlock& block, LaneMemory& memory,
                                           double /*t*/, double h) {
  using B = typename T::batch_type;
  constexpr int K = T::batches;
  namespace rows = dmv_rows;
  auto ld = [](const double* p) { return load<B, K>(p); };
  T P[3], cP[3], hist[6][3];
  for (int i = 0; i < 3; ++i) P[i] = ld(block.row[9 + i]), cP[i] = ld(memory.row[rows::carry_Pi + i]);
  for (int m = 0; m < 6; ++m)
    for (int i = 0; i < 3; ++i) hist[m][i] = ld(memory.row[rows::history + 3 * m + i]);
  const T count = ld(memory.row[rows::count]), h_history = ld(memory.row[rows::step]);
  auto ok = equal(count, 6.0) & less_equal(abs(h - h_history), 1e-6 * abs(h_history));
  // Not turning too far, and the truncated series positive.
  const double Jd[3] = {model.J_inv[0][0], model.J_inv[1][1], model.J_inv[2][2]};
  const T v0 = Jd[0] * P[0], v1 = Jd[1] * P[1], v2 = Jd[2] * P[2];
  ok = ok & less((h * h) * ((v0 * v0 + v1 * v1) + v2 * v2), T(std::numbers::pi * std::numbers::pi));
  T mu[3], two_mu[3], d[3], bound, a[3], guess[3], w[3], f[3];
  ok = ok & dmv_detail::moments_for<T>(model, memory, h, mu, two_mu, d, bound);
  for (int i = 0; i < 3; ++i) {
    a[i] = h * P[i];
    guess[i] = h * (((6.0 * hist[0][i] - 15.0 * hist[1][i]) + (20.0 * hist[2][i] - 15.0 * hist[3][i])) +
                    (6.0 * hist[4][i] - hist[5][i]));
  }
  ok = ok & dmv_detail::predicted_parameter(mu, two_mu, d, bound, a, guess, w, f);
  const moser_veselov::CayleyIncrement<T> F(f);
  T P1[3] = {P[0], P[1], P[2]}, cP1[3] = {cP[0], cP[1], cP[2]};
  dmv_detail::rotate_momentum(F, P1, cP1);
  // Only the lanes that passed change; the others keep their state and memory for the scalar step.
  for (int i = 0; i < 3; ++i) {
    store(select(ok, P1[i], P[i]), block.row[9 + i]);
    store(select(ok, cP1[i], cP[i]), memory.row[rows::carry_Pi + i]);
  }
  if (model.preprocessed) {  // the attitude is q (rows::quaternion), block's R rows are left
    T q[4], cq[4], q1[4], cq1[4];
    for (int i = 0; i < 4; ++i)
      q[i] = q1[i] = ld(memory.row[rows::quaternion + i]), cq[i] = cq1[i] = ld(memory.row[rows::quaternion_carry + i]);
    dmv_detail::rotate_quaternion(F, f, q1, cq1);
    for (int i = 0; i < 4; ++i) {
      store(select(ok, q1[i], q[i]), memory.row[rows::quaternion + i]);
      store(select(ok, cq1[i], cq[i]), memory.row[rows::quaternion_carry + i]);
    }
  } else {
    T R[9], cR[9], R1[9], cR1[9];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        R[3 * i + j] = R1[3 * i + j] = ld(block.row[3 * i + j]),
                  cR[3 * i + j] = cR1[3 * i + j] = ld(memory.row[rows::carry_R + i + 3 * j]);
    dmv_detail::rotate_matrix(F, R1, cR1);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        store(select(ok, R1[3 * i + j], R[3 * i + j]), block.row[3 * i + j]);
        store(select(ok, cR1[3 * i + j], cR[3 * i + j]), memory.row[rows::carry_R + i + 3 * j]);
      }
  }
  for (int m = 5; m >= 0; --m)
    for (int i = 0; i < 3; ++i)
      store(select(ok, m == 0 ? (1.0 / h) * w[i] : hist[m - 1][i], hist[m][i]), memory.row[rows::history + 3 * m + i]);
  store(select(ok, T(1.0), T(0.0)), memory.row[rows::stepped]);
  return active_lanes_clear<T>(block, memory, ok);
}

}  // namespace lgi::integrators::ensemble

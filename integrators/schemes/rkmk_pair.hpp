#pragma once
// Adaptive RKMK on any embedded Runge–Kutta pair, with a PI step-size
// controller and, where the pair has one, dense output (`rkmk-dp54`,
// `rkmk-verner65`, `rkmk-dop853`, `rkmk-verner87`, `rkmk-verner98`;
// registry_lie_group_runge_kutta.cpp, registry_verner_pairs.cpp).
//
// Stages (Munthe-Kaas, Appl. Numer. Math. 29 (1999) 115–127, Algorithm 1;
// Iserles et al., Acta Numerica 9 (2000) §5.3, eq. (5.14); body form as in
// rkmk.hpp, docs/math.md §2): for i = 1..s
//   w_i = Σ_j (h a_ij) k̃_j,  Π_i = Π_n + Σ_j (h a_ij) K_j,  Ω_i = J⁻¹Π_i,  R_i = R_n exp(w_i),
//   k̃_i = dexp⁻¹_body(w_i) Ω_i = Ω_i + ½ w_i × Ω_i + c(θ_i) w_i × (w_i × Ω_i),
//   K_i = Π_i × Ω_i + τ(R_i, Π_i, Ω_i, t_n + c_i h),
//   R_{n+1} = R_n exp(Σ (h b_i) k̃_i),  Π_{n+1} = Π_n + Σ (h b_i) K_i.
// RKMK is the pair applied to the chart ODE w' = dexp⁻¹(w) Ω, Π' = K in the
// coordinates R = R_n exp(w), so the pair's order, its embedded solutions
// and its continuous extension carry over (Munthe-Kaas 1999, Thm. 1; Engø,
// BIT 40 (2000) 41–61, for the error estimate):
//   e_ξ = h Σ (b_i − b̂_i) k̃_i (radians, absolute),  e_Π = h Σ (b_i − b̂_i) K_i
//   (relative to M = max(|Π_n|, |Π_{n+1}|, h|K_1|)),
//   E(e) = sqrt((|e_ξ|²/tol² + |e_Π|²/(tol M)²)/6),
//   err = E(e) for an embedded pair, err = E(e5)²/sqrt(E(e5)² + 0.01 E(e3)²)
//   for DOP853's 8(5,3) estimator (HNW I §II.10).
// exp(w) and dexp⁻¹(w) share one sin/cos of θ/2, or a Taylor series below
// θ = 1 (rkmk_pair_kernels.hpp). The stage attitude R_i is formed only when
// the model has a torque, and only the rows the torque reads (gravity: Γ = Rᵀe3).
//
// Step control: PI controller (Gustafsson, ACM TOMS 17 (1991) 533–554;
// HNW I §II.4 after eq. (4.13); the form of Hairer's DOPRI5/DOP853 codes):
//   accepted: h_new = h · clamp(s · err_n^(−α) · err_{n−1}^β, f_min, f_max),
//   α = 1/q − 0.75 β, q the order of err's leading term (p̂ + 1; 8 for 8(5,3)),
//   err_{n−1} the last accepted err (at least 1e-4), no growth right after a
//   rejection; rejected: h_new = h · max(f_min, s · err^(−α)). β = 0 is the
//   I controller of HNW I eq. (4.13). Its logarithms, exponential and the
//   initial step's power are controller_math.hpp's, not libm's: the same steps
//   on every CPU.
//
// Dense output (interpolate()): the pair's continuous extension in the chart,
//   w(θ) = h Σ b_i(θ) k̃_i,  Π(θ) = Π_n + h Σ b_i(θ) K_i,  R(θ) = R_n exp(w(θ)),
// of the pair's dense order q (embedded_pairs.hpp); its extra stages and the
// evaluation at the new point are computed at the first interpolate() of a
// step, and counted with the next step's evaluations.
//
// Coordinates: the exponential by default; with Chart = CayleyChart
// (rkmk_chart.hpp) exp and dexp⁻¹ above become cay and dcay⁻¹
// (`rkmk-cayley-*`), the same order (docs/math.md §2).
// Order: that of the pair. Conserves RᵀR = I to round-off (the attitude only
// moves by exp or cay); no invariant of the dynamics exactly.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "integrators/core/controller_math.hpp"
#include "integrators/core/flatten_policy.hpp"
#include "integrators/schemes/rkmk_chart.hpp"
#include "integrators/schemes/rkmk_pair_kernels.hpp"
#include "integrators/core/scheme_interface.hpp"
#include "integrators/tableaus/embedded_pairs.hpp"

namespace lgi::integrators {

/// The PI controller's constants (top of this file).
struct PairControl {
  double exponent = 0.2;  // 1/q
  double beta = 0.0;      // the err_{n−1} exponent; 0: the I controller
  double safety = 0.9;
  double fac_min = 0.2;
  double fac_max = 5.0;
};

namespace rkmk_pair_detail {

template <class P>
concept dense_pair = requires { P::dense_stages; };

template <class P>
constexpr std::size_t dense_degree() {
  if constexpr (dense_pair<P>) return P::dense_degree;
  else return 0;
}

template <class P>
constexpr std::size_t stored_stages() {
  if constexpr (dense_pair<P>) return P::dense_stages;
  else return P::stages;
}

}  // namespace rkmk_pair_detail

template <const auto& Pair, const PairControl& Control, RkmkChart Chart = ExponentialChart>
class RkmkPair {
  using P = std::remove_cvref_t<decltype(Pair)>;

 public:
  static constexpr auto& tableau = Pair;
  using chart = Chart;
  static constexpr std::size_t stages = P::stages;
  static constexpr bool dense = rkmk_pair_detail::dense_pair<P>;
  static constexpr bool fsal = Pair.first_same_as_last;
  static constexpr SchemeFacts facts{.order = Pair.order,
                                     .properties = {.adaptive = true},
                                     .reference = Chart::reference,
                                     .tableau = Pair.citation};

  explicit RkmkPair(double tol = 1e-8) : tol_(tol) {}
  double tolerance() const { return tol_; }

  /// Resume (scheme_interface.hpp): the controller's memory (last rejection,
  /// log err_{n−1}), the cached first stage and the dense output's evaluations
  /// not yet counted, 7 numbers.
  void save_memory(std::vector<double>& out) const {
    out.push_back(static_cast<double>(pending_evaluations_));
    out.push_back(last_rejected_ ? 1.0 : 0.0);
    out.push_back(first_valid_ ? 1.0 : 0.0);
    out.push_back(log_err_previous_);
    for (int i = 0; i < 3; ++i) out.push_back(first_K_(i));
  }
  bool restore_memory(std::span<const double> in) {
    if (in.size() != 7 || !(in[0] >= 0.0 && in[0] < 1e9) || in[0] != std::floor(in[0])) return false;
    const auto pending = static_cast<std::int64_t>(in[0]);
    in = in.subspan(1);
    if ((in[0] != 0.0 && in[0] != 1.0) || (in[1] != 0.0 && in[1] != 1.0) ||
        !(in[2] >= log_err_floor && std::isfinite(in[2])))
      return false;
    pending_evaluations_ = pending;
    last_rejected_ = in[0] == 1.0;
    first_valid_ = in[1] == 1.0;
    log_err_previous_ = in[2];
    first_K_ = Vec3(in[3], in[4], in[5]);
    dense_ready_ = false;
    return true;
  }

  /// A starting step from the initial field (HNW I, §II.4, simplified):
  /// h0 = 0.5 · tol^(1/q) / max(|Ω|, |Π̇|/|Π|), capped by the span.
  template <class Model>
  double initial_step(const Model& model, const State& s, double t, double span) const {
    const Vec3 O = model.omega(s.Pi);
    const Vec3 K = model.momentum_rate(s.R, s.Pi, O, t);
    const double pn = s.Pi.norm();
    double rate = O.norm();
    if (pn > 0.0) rate = std::max(rate, K.norm() / pn);
    if (!(rate > 0.0)) return span;
    return std::min(span, 0.5 * controller_math::pow(tol_, Control.exponent) / rate);
  }

  /// One fixed step of the propagated solution, accepted whatever the error
  /// estimate says: the pair used as a plain RKMK method (order verification).
  template <class Model>
  StepStatus step(const Model& model, State& s, double t, double h, WorkCounters& work) {
    attempt(model, s, t, h, work, true);
    return {};
  }

  template <class Model>
  AdaptiveStatus attempt(const Model& model, State& s, double t, double h, WorkCounters& work,
                         bool force_accept = false) {
    work.rhs_evaluations += pending_evaluations_;
    pending_evaluations_ = 0;
    R_n_ = s.R;
    Pi_n_ = s.Pi;
    t_n_ = t;
    h_ = h;
    dense_ready_ = false;
    torque_rows_ = rkmk_pair_detail::torque_rows(model);
    work.rhs_evaluations += run_stages(model, std::make_index_sequence<stages>{});

    // The propagated solution: for an FSAL pair the last stage sits there.
    std::array<double, 3> w_new;
    Vec3 Pi_new;
    Slope z{};  // Σ (h b_i) k_i, as the dense output's stage at the new point forms it
    if constexpr (fsal) {
      w_new = w_last_;
      Pi_new = Pi_last_;
    } else {
      z = rkmk_pair_detail::combination<b_weights, stages>(k_, h);
      w_new = {z[0], z[1], z[2]};
      Pi_new = Vec3(Pi_n_(0) + z[3], Pi_n_(1) + z[4], Pi_n_(2) + z[5]);
    }
    const ErrorNorm e = error_norm(h, Pi_new, z);
    const double err = e.err;

    AdaptiveStatus out;
    out.error_norm = err;
    const bool finite = std::isfinite(err);
    out.accepted = force_accept || (finite && err <= 1.0);
    // err^(−α) err_{n−1}^β as one exp of logarithms (two pow() cost 5% of a DOP853 step).
    const double log_err = finite ? std::max(e.log_err, log_err_min) : 0.0;
    double factor = Control.fac_min;
    if (out.accepted) {
      if (finite) factor = Control.safety * controller_math::exp(-alpha * log_err + Control.beta * log_err_previous_);
      factor = std::clamp(factor, Control.fac_min, Control.fac_max);
      if (last_rejected_) factor = std::min(factor, 1.0);
      last_rejected_ = false;
      if (finite) log_err_previous_ = std::max(log_err, log_err_floor);
      if constexpr (fsal && Model::has_torque) {
        s.R = R_last_;  // R_n φ(w_s), formed at the last stage
      } else {
        s.R = times_map<Chart>(R_n_, w_new.data());
      }
      s.Pi = Pi_new;
      // FSAL: the last stage's K is the next step's K_1. Otherwise the next
      // step evaluates it (or interpolate() does, for the dense output).
      if constexpr (fsal) first_K_ = Vec3(k_[stages - 1][3], k_[stages - 1][4], k_[stages - 1][5]);
      first_valid_ = fsal;
    } else {
      if (finite) factor = Control.safety * controller_math::exp(-alpha * log_err);
      factor = std::clamp(factor, Control.fac_min, 1.0);
      last_rejected_ = true;
      ++work.rejected_steps;
    }
    out.h_next = h * factor;
    return out;
  }

  /// The state at time t inside the last accepted step (the pair's dense output).
  template <class Model>
  void interpolate(const Model& model, double t, State& out)
    requires dense
  {
    if (!dense_ready_) prepare_dense(model);
    const double theta = (t - t_n_) / h_;
    constexpr std::size_t D = P::dense_degree;
    std::array<double, D + 1> basis{};  // B_k(θ) = C(D,k) θ^k (1 − θ)^(D−k), for a Bernstein pair
    if constexpr (Pair.bernstein) {
      double up = 1.0;
      for (std::size_t k = 0; k <= D; ++k, up *= theta) basis[k] = up;
      double down = 1.0;
      for (std::size_t k = D + 1; k-- > 0; down *= 1.0 - theta) basis[k] *= binomials[k] * down;
    }
    Slope z{};
    for (std::size_t i = 0; i < P::dense_stages; ++i) {
      double bi = 0.0;  // b_i(θ): Σ β_k,i B_k(θ), or by Horner's rule on the monomial coefficients
      if constexpr (Pair.bernstein) {
        for (std::size_t k = 0; k <= D; ++k) bi += Pair.dense[k][i] * basis[k];
      } else {
        for (std::size_t k = D; k >= 1; --k) bi = (bi + Pair.dense[k][i]) * theta;
      }
      for (std::size_t d = 0; d < 6; ++d) z[d] += bi * k_[i][d];
    }
    const double w[3] = {h_ * z[0], h_ * z[1], h_ * z[2]};
    out.R = times_map<Chart>(R_n_, w);
    out.Pi = Vec3(Pi_n_(0) + h_ * z[3], Pi_n_(1) + h_ * z[4], Pi_n_(2) + h_ * z[5]);
  }

 private:
  using Slope = rkmk_pair_detail::Slope;
  static constexpr std::size_t stored = rkmk_pair_detail::stored_stages<P>();
  static constexpr double alpha = Control.exponent - 0.75 * Control.beta;
  /// C(D, k), the Bernstein basis's factors (interpolate()).
  static constexpr auto binomials = [] {
    std::array<double, rkmk_pair_detail::dense_degree<P>() + 1> c{};
    for (std::size_t k = 0; k < c.size(); ++k) c[k] = tableaus::detail::binomial(c.size() - 1, k);
    return c;
  }();
  static constexpr double log_err_floor = -9.210340371976184;  // log(1e-4), Hairer's floor of err_{n−1}
  static constexpr double log_err_min = -23.025850929940457;   // log(1e-10), the floor of err_n

  /// Ω = J⁻¹Π, written out for RigidBody models (Eigen's 3 × 3 product was not
  /// inlined in the stage loop); the model's omega() otherwise.
  template <class Model>
  [[gnu::always_inline]] static Vec3 omega_of(const Model& model, const Vec3& Pi) {
    if constexpr (requires { model.inertia.J_inv; }) {
      const Mat3& J = model.inertia.J_inv;
      // A diagonal J⁻¹ (J's off-diagonal entries exactly 0) gives the same
      // products without the zero terms, one multiply deep on the stage's
      // critical path Π_i → Ω_i → K_i instead of three operations.
      if (model.inertia.diagonal) return Vec3(J(0, 0) * Pi(0), J(1, 1) * Pi(1), J(2, 2) * Pi(2));
      return Vec3(J(0, 0) * Pi(0) + J(0, 1) * Pi(1) + J(0, 2) * Pi(2),
                  J(1, 0) * Pi(0) + J(1, 1) * Pi(1) + J(1, 2) * Pi(2),
                  J(2, 0) * Pi(0) + J(2, 1) * Pi(1) + J(2, 2) * Pi(2));
    } else {
      return model.omega(Pi);
    }
  }

  /// Row I of the extended tableau's a (the rows past the step's stages are
  /// the new point's and the dense output's), as combination()'s weights.
  template <std::size_t I>
  static constexpr std::array<double, stored> a_row = [] {
    std::array<double, stored> row{};
    for (std::size_t j = 0; j < I; ++j) {
      if constexpr (I < stages) row[j] = Pair.a[I][j];
      else row[j] = Pair.extended.a[I][j];
    }
    return row;
  }();
  template <std::size_t I>
  static constexpr double c_i() {
    if constexpr (I < stages) return Pair.c[I];
    else return Pair.extended.c[I];
  }
  static constexpr std::array<double, stages> difference(const std::array<double, stages>& x,
                                                         const std::array<double, stages>& y) {
    std::array<double, stages> d{};
    for (std::size_t i = 0; i < stages; ++i) d[i] = x[i] - y[i];
    return d;
  }
  static constexpr std::array<double, stages> b_weights = Pair.b;
  static constexpr std::array<double, stages> error_weights = difference(Pair.b, Pair.b_hat);
  static constexpr std::array<double, stages> low_weights = [] {
    if constexpr (requires { Pair.b_low; }) return Pair.b_low;
    else return std::array<double, stages>{};
  }();
  static constexpr std::array<double, stages> low_error_weights = [] {
    if constexpr (requires { Pair.b_low; }) return difference(Pair.b, Pair.b_low);
    else return std::array<double, stages>{};
  }();
  static constexpr bool two_estimates = [] {
    if constexpr (requires { Pair.low_order; }) return Pair.low_order > 0;
    else return false;
  }();

  /// Stage I of the extended tableau from stages 0..I−1: fills k_[I] (and, at
  /// the step's last stage, w, Π and R there). Returns its evaluations (0 or 1).
  template <std::size_t I, class Model>
  int stage(const Model& model) {
    if constexpr (I == 0) {
      const Vec3 Omega = omega_of(model, Pi_n_);
      if (!first_valid_) {
        first_K_ = model.momentum_rate(R_n_, Pi_n_, Omega, t_n_);  // kept for a retry after a rejection
        first_valid_ = true;
        set_slope(0, Omega, first_K_);
        return 1;
      }
      set_slope(0, Omega, first_K_);
      return 0;
    } else {
      // z = Σ_J (h a_IJ) k_J: the products h a_IJ do not wait for the slopes,
      // so w_i is one multiply-add after the last slope instead of two.
      const Slope z = rkmk_pair_detail::combination<a_row<I>, I>(k_, h_);
      const double w[3] = {z[0], z[1], z[2]};
      const Vec3 Pi_i(Pi_n_(0) + z[3], Pi_n_(1) + z[4], Pi_n_(2) + z[5]);
      const Vec3 Omega_i = omega_of(model, Pi_i);
      const auto m = Chart::coefficients(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
      Chart::inverse_differential(w, Omega_i, m, k_[I].data());
      Vec3 K;
      if constexpr (Model::has_torque) {
        // FSAL: the last stage's attitude is the new point's, needed whole.
        if constexpr (fsal && I == stages - 1) {
          R_last_ = rkmk_pair_detail::times_exp(R_n_, w, m);  // R_n φ(ŵ) from the chart's a, b
          K = model.momentum_rate(R_last_, Pi_i, Omega_i, t_n_ + c_i<I>() * h_);
        } else {
          Mat3 R_i;
          rkmk_pair_detail::stage_attitude(R_n_, w, m, torque_rows_, R_i);
          K = model.momentum_rate(R_i, Pi_i, Omega_i, t_n_ + c_i<I>() * h_);
        }
      } else {
        K = model.momentum_rate(R_n_, Pi_i, Omega_i, t_n_);
      }
      k_[I][3] = K(0);
      k_[I][4] = K(1);
      k_[I][5] = K(2);
      if constexpr (I == stages - 1) {
        w_last_ = {w[0], w[1], w[2]};
        Pi_last_ = Pi_i;
      }
      return 1;
    }
  }

  void set_slope(std::size_t i, const Vec3& xi_rate, const Vec3& momentum_rate) {
    for (int d = 0; d < 3; ++d) {
      k_[i][static_cast<std::size_t>(d)] = xi_rate(d);
      k_[i][static_cast<std::size_t>(d + 3)] = momentum_rate(d);
    }
  }

  // flatten: every call in the stages (the maps' coefficients, dexp⁻¹, the
  // stage attitude, the model's torque) is inlined into this one function, so
  // GCC schedules and vectorises the stage chain as a whole. Same bits;
  // rkmk-dop853 on HLW's top at tol 1e-10 went from 30.8 to 27.7 µs
  // (interleaved A/B runs of lgi work-precision, docs/performance.md §2).
  template <class Model, std::size_t... I>
  LGI_FLATTEN std::int64_t run_stages(const Model& model, std::index_sequence<I...>) {
    return (static_cast<std::int64_t>(stage<I>(model)) + ...);
  }

  /// |e_ξ|² (tol M)² + |e_Π|² tol² for e = h Σ W_i k_i: 6 tol² (tol M)² E(e)²
  /// (top of this file), the numerator over the denominator all estimates share.
  double error_numerator(const Slope& e, double momentum_scale2) const {
    const double xi2 = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
    const double pi2 = e[3] * e[3] + e[4] * e[4] + e[5] * e[5];
    return xi2 * momentum_scale2 + pi2 * (tol_ * tol_);
  }

  /// err (top of this file) and its logarithm, which the controller needs. With
  /// E(e)² = n / D, D = 6 tol² (tol M)², err is sqrt(n5 / D), or n5 / sqrt(D (n5 +
  /// 0.01 n3)) for DOP853, and log err a sum of logarithms: no division or square
  /// root lies between the last stage and the next step's h (the controller's
  /// chain of dependent operations). M² = max(|Π_n|², |Π_{n+1}|², h²|K_1|²).
  /// z = h Σ b_i k_i (a pair without FSAL): DOP853's e3 = z − h Σ b̌_i k_i then
  /// takes the three stages of b̌, as Hairer's code does, instead of eight.
  struct ErrorNorm {
    double err, log_err;
  };
  ErrorNorm error_norm(double h, const Vec3& Pi_new, const Slope& z) const {
    const double K1 = k_[0][3] * k_[0][3] + k_[0][4] * k_[0][4] + k_[0][5] * k_[0][5];
    const double momentum_scale2 =
        tol_ * tol_ * std::max({Pi_n_.squaredNorm(), Pi_new.squaredNorm(), h * h * K1, 1e-300});
    const double D = 6.0 * (tol_ * tol_) * momentum_scale2;
    const double n5 =
        error_numerator(rkmk_pair_detail::combination<error_weights, stages>(k_, h), momentum_scale2);
    if constexpr (two_estimates) {
      Slope e{};
      if constexpr (fsal) {
        e = rkmk_pair_detail::combination<low_error_weights, stages>(k_, h);
      } else {
        const Slope low = rkmk_pair_detail::combination<low_weights, stages>(k_, h);
        for (std::size_t d = 0; d < 6; ++d) e[d] = z[d] - low[d];
      }
      const double n = n5 + 0.01 * error_numerator(e, momentum_scale2);
      if (!(n > 0.0)) return {0.0, -HUGE_VAL};
      return {n5 / std::sqrt(D * n), controller_math::log(n5) - 0.5 * (controller_math::log(D) + controller_math::log(n))};
    } else {
      return {std::sqrt(n5 / D), 0.5 * (controller_math::log(n5) - controller_math::log(D))};
    }
  }

  /// The stages past the step's (the new point for a pair without FSAL, and
  /// the dense output's extra stages), from the stored stages of the step.
  template <class Model>
  void prepare_dense(const Model& model)
    requires dense
  {
    pending_evaluations_ += [&]<std::size_t... I>(std::index_sequence<I...>) {
      return (static_cast<std::int64_t>(stage<stages + I>(model)) + ... + 0);
    }(std::make_index_sequence<P::dense_stages - stages>{});
    if constexpr (!fsal) {
      // Stage `stages` is the new point: its K is the next step's K_1.
      first_K_ = Vec3(k_[stages][3], k_[stages][4], k_[stages][5]);
      first_valid_ = true;
    }
    dense_ready_ = true;
  }

  double tol_;
  bool last_rejected_ = false;
  bool first_valid_ = false;  // first_K_ holds K at the current state (the next attempt's K_1)
  bool dense_ready_ = false;
  double log_err_previous_ = log_err_floor;  // log err_{n−1}
  std::int64_t pending_evaluations_ = 0;
  // The last attempt: its start, step and stages, and w, Π, R at its last stage.
  Mat3 R_n_ = Mat3::Identity();
  Vec3 Pi_n_ = Vec3::Zero();
  double t_n_ = 0.0, h_ = 0.0;
  std::array<Slope, stored> k_{};
  std::array<double, 3> w_last_{};
  Vec3 Pi_last_ = Vec3::Zero();
  Mat3 R_last_ = Mat3::Identity();
  unsigned torque_rows_ = 0b111u;  // the rows of a stage attitude the torque reads
  Vec3 first_K_ = Vec3::Zero();
};

}  // namespace lgi::integrators

#pragma once
// Adaptive RKMK on an embedded pair: Dormand–Prince 5(4) (`rkmk-dp54`).
//
// The RKMK stages of rkmk.hpp with the DP5(4) tableau (Dormand & Prince
// 1980). The local error is estimated on the Lie algebra and in Π
// (Munthe-Kaas 1999, §4; Engø, "On the construction of geometric
// integrators in the RKMK class", BIT 40 (2000)):
//   e_ξ = h Σ (b_i − b̂_i) k̃_i,   e_Π = h Σ (b_i − b̂_i) K_i,
//   err = RMS(e_ξ / tol, e_Π / (tol · max(|Π_n|, |Π_{n+1}|)))
// (the attitude error is absolute in radians; the momentum error relative,
// so results do not depend on the units). Step control as in HNW I, §II.4,
// eq. (4.13): h_new = h · min(5, max(0.2, 0.9 err^(−1/5))), no growth right
// after a rejection. The propagated solution is the 5th-order one. FSAL:
// the last stage's field evaluation is the next step's first.
// Order 5; conserves RᵀR = I to round-off.
#include <algorithm>
#include <array>
#include <cmath>

#include "integrators/scheme_interface.hpp"
#include "integrators/tableaus/runge_kutta.hpp"

namespace lgi::integrators {

class RkmkDp54 {
 public:
  static constexpr auto& tableau = tableaus::dormand_prince54;
  static constexpr SchemeFacts facts{.order = tableau.order,
                                     .properties = {.adaptive = true},
                                     .reference = munthe_kaas_reference,
                                     .tableau = tableau.citation};
  static constexpr std::size_t stages = 7;

  explicit RkmkDp54(double tol = 1e-8) : tol_(tol) {}
  double tolerance() const { return tol_; }

  /// A starting step from the initial field (HNW I, §II.4, simplified):
  /// h0 = 0.01 · tol^(1/5) / max(|Ω|, |Π̇|/|Π|), capped by the span.
  template <class Model>
  double initial_step(const Model& model, const State& s, double t, double span) const {
    const Vec3 O = model.omega(s.Pi);
    const Vec3 K = model.momentum_rate(s.R, s.Pi, O, t);
    const double pn = s.Pi.norm();
    double rate = O.norm();
    if (pn > 0.0) rate = std::max(rate, K.norm() / pn);
    if (!(rate > 0.0)) return span;
    return std::min(span, 0.5 * std::pow(tol_, 0.2) / rate);
  }

  /// One fixed step of the 5th-order solution, accepted whatever the error
  /// estimate says: the pair used as a plain RKMK method (order verification).
  template <class Model>
  StepStatus step(const Model& model, State& s, double t, double h, WorkCounters& work) {
    attempt(model, s, t, h, work, true);
    return {};
  }

  template <class Model>
  AdaptiveStatus attempt(const Model& model, State& s, double t, double h, WorkCounters& work,
                         bool force_accept = false) {
    const auto& T = tableau;
    std::array<Vec3, stages> k_algebra;
    std::array<Vec3, stages> k_momentum;
    std::array<Vec3, stages> stage_momentum;
    std::array<Mat3, stages> stage_attitude;
    std::array<Vec3, stages> stage_w;
    std::int64_t evaluations = 0;
    for (std::size_t i = 0; i < stages; ++i) {
      Vec3 w = Vec3::Zero();
      Vec3 dPi = Vec3::Zero();
      for (std::size_t j = 0; j < i; ++j) {
        const double aij = T.a[i][j];
        if (aij == 0.0) continue;
        w += aij * k_algebra[j];
        dPi += aij * k_momentum[j];
      }
      w *= h;
      stage_w[i] = w;
      stage_momentum[i] = s.Pi + h * dPi;
      const Vec3 Omega_i = model.omega(stage_momentum[i]);
      k_algebra[i] = i == 0 ? Omega_i : lie::dexpinv_body(w, Omega_i);
      if (i == 0 && fsal_valid_) {
        k_momentum[0] = fsal_momentum_rate_;
        continue;
      }
      if constexpr (Model::has_torque) {
        stage_attitude[i] = i == 0 ? s.R : Mat3(s.R * lie::exp_so3(w));
        k_momentum[i] = model.momentum_rate(stage_attitude[i], stage_momentum[i], Omega_i, t + T.c[i] * h);
      } else {
        k_momentum[i] = model.momentum_rate(s.R, stage_momentum[i], Omega_i, t);
      }
      ++evaluations;
    }
    work.rhs_evaluations += evaluations;

    // Row 7 of A is b, so stage 7 sits at the 5th-order solution.
    const Vec3 w_new = stage_w[stages - 1];
    const Vec3 Pi_new = stage_momentum[stages - 1];
    Vec3 e_xi = Vec3::Zero();
    Vec3 e_Pi = Vec3::Zero();
    for (std::size_t i = 0; i < stages; ++i) {
      const double d = T.b[i] - T.b_hat[i];
      e_xi += d * k_algebra[i];
      e_Pi += d * k_momentum[i];
    }
    e_xi *= h;
    e_Pi *= h;
    const double momentum_scale = tol_ * std::max({s.Pi.norm(), Pi_new.norm(), std::abs(h) * k_momentum[0].norm(),
                                                   1e-300});
    const double err = std::sqrt((e_xi.squaredNorm() / (tol_ * tol_) +
                                  e_Pi.squaredNorm() / (momentum_scale * momentum_scale)) / 6.0);

    AdaptiveStatus out;
    out.error_norm = err;
    const bool finite = std::isfinite(err);
    out.accepted = force_accept || (finite && err <= 1.0);
    double factor = finite ? 0.9 * std::pow(std::max(err, 1e-10), -0.2) : 0.2;
    factor = std::clamp(factor, 0.2, 5.0);
    if (out.accepted) {
      if (last_rejected_) factor = std::min(factor, 1.0);
      last_rejected_ = false;
      s.R = s.R * lie::exp_so3(w_new);
      s.Pi = Pi_new;
      // FSAL: K at (R_{n+1}, Π_{n+1}, t + h) is the next step's K_1.
      fsal_momentum_rate_ = k_momentum[stages - 1];
      fsal_valid_ = true;
    } else {
      last_rejected_ = true;
      ++work.rejected_steps;
    }
    out.h_next = h * factor;
    return out;
  }

 private:
  double tol_;
  bool last_rejected_ = false;
  bool fsal_valid_ = false;
  Vec3 fsal_momentum_rate_ = Vec3::Zero();
};

}  // namespace lgi::integrators

#pragma once
// The arithmetic of one RKMK stage on SO(3) × ℝ³ (rkmk_pair.hpp), written on
// plain doubles: in a 12-stage step GCC stops inlining Eigen's fixed-size
// kernels (each Vec3 axpy became a call), which cost half the step. Every
// formula here is one of lie/so3.hpp, evaluated in the same way.
//
// exp(ŵ) = I + a ŵ + b ŵ² and dexp⁻¹_body(w) Ω = Ω + ½ w × Ω + c w × (w × Ω)
// with their coefficients from lie/exp_series.hpp (the Taylor series below
// θ = 1, shorter below θ = 1/2, or one sin/cos of θ/2), which rkmk.hpp and
// the ensemble kernel share.
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

#include "lie/exp_series.hpp"
#include "lie/so3.hpp"

namespace lgi::integrators::rkmk_pair_detail {

using lie::Mat3;
using lie::Vec3;

/// A stage's derivatives in the chart: (k̃, K) = (dexp⁻¹(w) Ω, Π̇).
using Slope = std::array<double, 6>;

struct MapCoefficients {
  double a, b, c;
};

/// a, b, c from θ² = |w|² (lie/exp_series.hpp: the short series below
/// θ = 1/2, the series below θ = 1, else one sin/cos of θ/2).
inline MapCoefficients map_coefficients(double t2) {
  namespace ex = lie::exp_series;
  if (t2 < ex::short_series_bound) return {ex::series_a<true>(t2), ex::series_b<true>(t2), ex::series_c<true>(t2)};
  if (t2 < ex::series_bound) return {ex::series_a(t2), ex::series_b(t2), ex::series_c(t2)};
  const double theta = std::sqrt(t2);
  const double half = 0.5 * theta;
  const double s = std::sin(half), k = std::cos(half);
  return {ex::closed_a(theta, s, k), ex::closed_b(theta, s), ex::closed_c(t2, theta, s, k)};
}

/// The rows of R a model's torque reads (RigidBody::attitude_rows()); all
/// three for a model that does not say.
template <class Model>
unsigned torque_rows(const Model& model) {
  if constexpr (requires { model.attitude_rows(); }) return model.attitude_rows();
  else return 0b111u;
}

/// A stage attitude R exp(ŵ) as the torque needs it: the rows in `rows` (bit i:
/// row i, lie::exp_series::times_exp_row), the others NaN, so that a term
/// reading a row it did not declare makes the run fail instead of using a stale
/// row (torque_term.hpp). Gravity reads only Γ = Rᵀe3: one row's work instead of three.
inline void stage_attitude(const Mat3& R, const double* w, const MapCoefficients& m, unsigned rows, Mat3& out) {
  for (int i = 0; i < 3; ++i) {
    if ((rows >> i) & 1u) {
      const double r[3] = {R(i, 0), R(i, 1), R(i, 2)};
      double o[3];
      lie::exp_series::times_exp_row(r, w, m.a, m.b, o);
      out(i, 0) = o[0];
      out(i, 1) = o[1];
      out(i, 2) = o[2];
    } else {
      out.row(i).setConstant(std::numeric_limits<double>::quiet_NaN());
    }
  }
}

/// R exp(ŵ), every row.
inline Mat3 times_exp(const Mat3& R, const double* w, const MapCoefficients& m) {
  Mat3 out;
  stage_attitude(R, w, m, 0b111u, out);
  return out;
}

/// R exp(ŵ) for the rows in `rows` (NaN elsewhere; all three by default), its
/// coefficients from map_coefficients: the series below θ = 1, no sin or cos.
inline Mat3 times_exp(const Mat3& R, const double* w, unsigned rows = 0b111u) {
  Mat3 out;
  stage_attitude(R, w, map_coefficients(lie::exp_series::squared_norm(w)), rows, out);
  return out;
}
inline Mat3 times_exp(const Mat3& R, const Vec3& w, unsigned rows = 0b111u) { return times_exp(R, w.data(), rows); }

/// k̃ = dexp⁻¹_body(w) Ω into out[0..2].
inline void dexpinv(const double* w, const Vec3& omega, const MapCoefficients& m, double* out) {
  const double o[3] = {omega(0), omega(1), omega(2)};
  lie::exp_series::dexpinv(w, o, m.c, out);
}

/// Σ_J (scale W[J]) k[J] over the first N slopes, zero weights skipped at
/// compile time: with scale = h, the sum a stage of the pair forms (its
/// w_i and Π_i − Π_n), so that a stage at node 1 with row b and the step's
/// new point round alike.
template <const auto& W, std::size_t N, std::size_t Stored>
inline Slope combination(const std::array<Slope, Stored>& k, double scale = 1.0) {
  Slope sum{};
  [&]<std::size_t... J>(std::index_sequence<J...>) {
    auto add = [&](double weight, const Slope& kj) {
      for (std::size_t d = 0; d < 6; ++d) sum[d] += weight * kj[d];
    };
    ((W[J] != 0.0 ? add(scale * W[J], k[J]) : void()), ...);
  }(std::make_index_sequence<N>{});
  return sum;
}

}  // namespace lgi::integrators::rkmk_pair_detail

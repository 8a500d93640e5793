#pragma once
// The chaos indicators of any chosen state of an SO(3) scene, as `lgi
// indicators` and lgi.indicators() report them (experiments/INDICATORS.md):
// the largest Lyapunov exponent over the run and over its second half (the
// convergence estimate), MEGNO ⟨Y⟩, and on request the full spectrum.
// The state and its tangent vector(s) are integrated together by
// integrators/tangent_flow.hpp (RKMK4 on SO(3) × ℝ³ × ℝ⁶).
//
// Spectrum: six tangent vectors, the columns of V (from the identity), are
// advanced with the state and re-orthonormalised after every step by modified
// Gram–Schmidt, V = QR; λ_k is the time average of ln R_kk (G. Benettin,
// L. Galgani, A. Giorgilli, J.-M. Strelcyn, Meccanica 15 (1980) 9–20 and
// 21–30). The values come in the Gram–Schmidt order, which is the descending
// order once the run is long enough.
#include <array>
#include <cstdint>

#include "integrators/system/scene.hpp"
#include "integrators/tangent_flow.hpp"

namespace lgi::experiments {

/// How the indicators are computed.
struct IndicatorSettings {
  double t_end = 0.0;
  double dt = 0.0;              // the step of the state and its tangent (the last one shortened)
  std::uint64_t seed = 0;       // the tangent vector's draw, with the state's index
  bool spectrum = false;
  double rtol = 0.05;           // converged: |λ[T/2,T] − λ[0,T]| ≤ rtol max(|λ[T/2,T]|, |λ[0,T]|)
};

struct StateIndicators {
  double lyapunov = 0.0;            // λ over [0, T]
  double lyapunov_last_half = 0.0;  // λ over [T/2, T]
  double megno = 0.0;               // ⟨Y⟩(T)
  double t_end = 0.0;
  bool converged = false;
  std::array<double, 6> spectrum{};  // NaN unless asked for
  bool ok = true;                    // false: the state or a tangent blew up (NaN values)
};

/// The unit-cube draw of the first tangent vector from (seed, index), the one
/// of `lgi poincare --lyapunov` and `lgi chaos-map` (normalised by the loop).
integrators::Vec6 initial_tangent(std::uint64_t seed, std::int64_t index);

/// |λ_half − λ| ≤ rtol · max(|λ_half|, |λ|), false on NaN (experiments/INDICATORS.md).
bool lyapunov_converged(double lyapunov, double last_half, double rtol);

/// The indicators of the state x0 of `scene` (an SO(3) scene) from t = 0; the
/// tangent vector starts at initial_tangent(seed, index).
StateIndicators state_indicators(const system::Scene& scene, const system::State& x0, const IndicatorSettings& s,
                                 std::int64_t index);

/// The six exponents of the Gram–Schmidt loop (top of this file) over [0, t_end]
/// with steps dt; NaN if the state or the vectors blew up.
std::array<double, 6> lyapunov_spectrum(const system::Scene& scene, const system::State& x0, double t_end, double dt);

}  // namespace lgi::experiments

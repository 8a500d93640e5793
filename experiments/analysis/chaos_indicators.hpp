#pragma once
// The chaos indicators of any chosen state of an SO(3) scene, as `lgi
// indicators` and lgi.indicators() report them (experiments/INDICATORS.md):
// the largest Lyapunov exponent over the run and over its second half (the
// convergence estimate), MEGNO ⟨Y⟩, and on request the full spectrum.
// The state and its tangent vector(s) are integrated together by
// integrators/core/tangent_flow.hpp (RKMK4 on SO(3) × ℝ³ × ℝ⁶), in the scalar form
// of its SIMD-lane kernel where the model has one
// (integrators/ensemble/tangent_ensemble.hpp, with_tangent_step).
//
// Spectrum: six tangent vectors, the columns of V (from the identity), are
// advanced with the state and re-orthonormalised after every step by modified
// Gram–Schmidt, V = QR; λ_k is the time average of ln R_kk (G. Benettin,
// L. Galgani, A. Giorgilli, J.-M. Strelcyn, Meccanica 15 (1980) 9–20 and
// 21–30). The values come in the Gram–Schmidt order, which is the descending
// order once the run is long enough.
//
// GALI_k (k = 2 … 6) on request: six more deviation vectors, normalised
// after every step, their volumes recorded at sample times (gali.hpp).
//
// Cardan scenes (T³ × ℝ³): the same indicators from the T³ tangent flow (RK4
// on ℝ⁶ × ℝ⁶) in the scalar form of its SIMD-lane kernel
// (integrators/ensemble/cardan_tangent_ensemble.hpp), cardan_state_indicators.
#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "experiments/analysis/gali.hpp"
#include "integrators/ensemble/ensemble.hpp"
#include "integrators/system/scene.hpp"
#include "integrators/core/tangent_flow.hpp"

namespace lgi::experiments {

/// How the indicators are computed.
struct IndicatorSettings {
  double t_end = 0.0;
  double dt = 0.0;              // the step of the state and its tangent (the last one shortened)
  std::uint64_t seed = 0;       // the tangent vector's draw, with the state's index
  bool spectrum = false;
  double rtol = 0.05;           // converged: |λ[T/2,T] − λ[0,T]| ≤ rtol max(|λ[T/2,T]|, |λ[0,T]|)
  bool gali = false;            // GALI_2 … GALI_6 at the sample times
  GaliSampling gali_sampling{};
};

struct StateIndicators {
  double lyapunov = 0.0;            // λ over [0, T]
  double lyapunov_last_half = 0.0;  // λ over [T/2, T]
  double megno = 0.0;               // ⟨Y⟩(T)
  double t_end = 0.0;
  bool converged = false;
  std::array<double, 6> spectrum{};  // NaN unless asked for
  GaliCurves gali{};                 // empty unless asked for
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

/// state_indicators of the states x0[k] (index first_index + k): bit for bit
/// the same, λ and ⟨Y⟩ computed in the SIMD lanes of a TangentEnsemble on `isa`
/// where the model has tangent kernels (integrators/ensemble/tangent_ensemble.hpp).
void state_indicators(const system::Scene& scene, std::span<const system::State> x0, const IndicatorSettings& s,
                      std::int64_t first_index, std::optional<integrators::ensemble::Isa> isa,
                      std::span<StateIndicators> out);

/// The indicators of the state x0 of the Cardan scene `scene` from t = 0, as
/// state_indicators (the same draws of the tangent vectors).
StateIndicators cardan_state_indicators(const system::Scene& scene, const system::TorusState& x0,
                                        const IndicatorSettings& s, std::int64_t index);

/// GALI_k (k = 2 … 6) of the state x0 over [0, t_end] with steps dt, the
/// deviation vectors from initial_deviation_vectors(seed, index); SO(3)
/// scenes (gali_curves) and Cardan scenes (cardan_gali_curves).
GaliCurves gali_curves(const system::Scene& scene, const system::State& x0, const IndicatorSettings& s,
                       std::int64_t index);
GaliCurves cardan_gali_curves(const system::Scene& scene, const system::TorusState& x0, const IndicatorSettings& s,
                              std::int64_t index);

/// The six exponents of the Gram–Schmidt loop (top of this file) over [0, t_end]
/// with steps dt; NaN if the state or the vectors blew up.
std::array<double, 6> lyapunov_spectrum(const system::Scene& scene, const system::State& x0, double t_end, double dt);

}  // namespace lgi::experiments

#pragma once
// The Cayley map and its inverse differential on so(3) ≅ ℝ³, written on plain
// numbers of any type T as lie/exp_series.hpp is, for coordinates R = R_n cay(ŵ):
//
//   cay(ŵ) = (I − ŵ/2)⁻¹(I + ŵ/2) = I + a ŵ + b ŵ²,   a = 4/(4 + θ²),  b = a/2,
//   dcay⁻¹_body(w) Ω = Ω + ½ w × Ω + ¼ (w·Ω) w,   θ = |w|
// (Iserles, Munthe-Kaas, Nørsett & Zanna, Acta Numerica 9 (2000) 215–365,
// the Cayley map of quadratic groups, dcay⁻¹_A(C) = (I − A/2) C (I + A/2),
// here in body form; docs/math.md §1). Rational, so no series, sin or cos:
// a rotation by 2 atan(θ/2), exact to round-off for every w.
namespace lgi::lie::cayley_coordinates {

/// a = 4/(4 + θ²) from θ² = t2 (b = a/2).
template <class T>
inline T coefficient(const T& t2) {
  return 4.0 / (4.0 + t2);
}

/// dcay⁻¹_body(w) Ω = Ω + ½ w × Ω + ¼ (w·Ω) w.
template <class T>
inline void dcayinv(const T* w, const T* omega, T* out) {
  const T x0 = w[1] * omega[2] - w[2] * omega[1], x1 = w[2] * omega[0] - w[0] * omega[2],
          x2 = w[0] * omega[1] - w[1] * omega[0];
  const T q = 0.25 * (w[0] * omega[0] + w[1] * omega[1] + w[2] * omega[2]);
  out[0] = omega[0] + 0.5 * x0 + q * w[0];
  out[1] = omega[1] + 0.5 * x1 + q * w[1];
  out[2] = omega[2] + 0.5 * x2 + q * w[2];
}

}  // namespace lgi::lie::cayley_coordinates

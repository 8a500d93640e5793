#pragma once
// Special functions the spectral statistics need and the C++ library lacks:
// the digamma and trigamma functions (the Brody fit's likelihood derivatives)
// and the sine and cosine integrals (the GOE number variance). Formulas:
// Abramowitz & Stegun, Handbook of Mathematical Functions (1964), 6.3.5,
// 6.3.18, 6.4.6, 6.4.12 (digamma, trigamma), 5.2.1, 5.2.14, 5.2.16 and 5.1.22
// (Si, Ci, E1's continued fraction); docs/spectral_statistics.md §6.

namespace lgi::experiments::spectral {

/// ψ(x) = Γ'(x)/Γ(x) for x > 0, to about 1e-13 absolute.
double digamma(double x);
/// ψ'(x) for x > 0, to about 1e-13 relative.
double trigamma(double x);
/// Si(x) = ∫₀ˣ sin(t)/t dt, any finite x (odd), to about 1e-14 absolute.
double sine_integral(double x);
/// Ci(x) = γ + ln x + ∫₀ˣ (cos t − 1)/t dt for x > 0, to about 1e-14 absolute.
double cosine_integral(double x);

}  // namespace lgi::experiments::spectral

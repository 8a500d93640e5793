#pragma once
// The reference statistics of unfolded spectra (docs/spectral_statistics.md §5):
// Poisson levels (integrable systems, M. V. Berry and M. Tabor, Proc. R. Soc.
// Lond. A 356 (1977) 375) and the Gaussian orthogonal ensemble (time-reversal
// invariant chaotic systems, O. Bohigas, M.-J. Giannoni and C. Schmit, Phys.
// Rev. Lett. 52 (1984) 1). GOE formulas: M. L. Mehta, Random Matrices, 3rd ed.
// 2004, ch. 16; Haake, Quantum Signatures of Chaos, 4th ed. 2018, ch. 4;
// O. Bohigas, Les Houches LII (1991) 87.
namespace lgi::experiments::spectral {

/// Poisson: P(s) = e^{−s}, Σ²(L) = L, Δ₃(L) = L/15.
double poisson_spacing_density(double s);
double poisson_number_variance(double length);
double poisson_rigidity(double length);

/// Wigner's surmise for the GOE: P(s) = (π/2) s exp(−π s²/4).
double wigner_spacing_density(double s);

/// The GOE number variance for N → ∞ (Mehta ch. 16; Bohigas):
/// Σ²(L) = (2/π²)[ln(2πL) + γ + 1 + Si(πL)²/2 − (π/2) Si(πL) − cos(2πL) − Ci(2πL)
///                 + π²L (1 − (2/π) Si(2πL))],
/// → (2/π²)(ln(2πL) + γ + 1 − π²/8) for large L.
double goe_number_variance(double length);

/// The GOE Δ₃(L) from Σ² (Pandey's relation, A. Pandey, Ann. Phys. 119 (1979) 170;
/// Bohigas): Δ₃(L) = (2/L⁴) ∫₀^L (L³ − 2L²r + r³) Σ²(r) dr, the integral
/// of a smooth function by composite Gauss–Legendre to about 1e-10;
/// → (1/π²)(ln(2πL) + γ − 5/4 − π²/8) for large L.
double goe_rigidity(double length);

/// The Gaussian unitary ensemble (chaotic systems without an antiunitary
/// symmetry, e.g. a general heavy top at m ≠ 0, docs/quantum.md §3; Mehta
/// ch. 6 and 16): Wigner's surmise P(s) = (32/π²) s² exp(−4s²/π), and
/// Σ²(L) = L − 2∫₀^L (L − r)(sin πr/(πr))² dr
///       = (1/π²)[ln(2πL) + γ + 1 − cos(2πL) − Ci(2πL)] + L(1 − (2/π) Si(2πL)),
/// → (1/π²)(ln(2πL) + γ + 1); Δ₃ by Pandey's relation,
/// → (1/(2π²))(ln(2πL) + γ − 5/4).
double gue_spacing_density(double s);
double gue_number_variance(double length);
double gue_rigidity(double length);

/// Δ₃(L) from any Σ²(r) by the same relation (panels of width at most 1/8,
/// 5 Gauss–Legendre points each).
double rigidity_from_number_variance(double length, double (*sigma2)(double));

}  // namespace lgi::experiments::spectral

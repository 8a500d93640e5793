#pragma once
// The Wigner basis |j, k, m⟩ of the rigid rotor at fixed m (docs/quantum.md):
// the functions √((2j+1)/8π²) D^j_{mk}(R)* (Zare, Angular Momentum, 1988,
// eq. 3.121), with ħm the angular momentum about the space vertical and ħk
// about the body's third axis. A block holds j = jlo..jhi (jlo ≥ |m|) and
// k = −j..j, ordered by j, then k.
#include <Eigen/Core>

namespace lgi::experiments::quantum {

struct WignerBasis {
  int m = 0;
  int jlo = 0, jhi = 0;

  /// j = |m|..jmax.
  static WignerBasis up_to(int m, int jmax) { return {m, m < 0 ? -m : m, jmax}; }
  /// The single j block.
  static WignerBasis single(int m, int j) { return {m, j, j}; }

  Eigen::Index offset(int j) const { return Eigen::Index{j} * j - Eigen::Index{jlo} * jlo; }
  Eigen::Index size() const { return offset(jhi + 1); }
  Eigen::Index index(int j, int k) const { return offset(j) + (k + j); }
  bool contains(int j, int k) const { return j >= jlo && j <= jhi && k >= -j && k <= j; }
  /// The (j, k) of a position.
  void label(Eigen::Index i, int& j, int& k) const;
};

/// The Clebsch–Gordan coefficient ⟨j1 m1; 1 q | J, m1 + q⟩ (Condon–Shortley
/// phases) from its closed form for j2 = 1 (Zare, Table 2.4; Edmonds, Angular
/// Momentum in Quantum Mechanics, Table 2); 0 unless |J − j1| ≤ 1 ≤ J + j1
/// and every projection is in range.
double clebsch_gordan_1(int j1, int m1, int q, int J);

}  // namespace lgi::experiments::quantum

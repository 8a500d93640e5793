#pragma once
// EBK levels of the Kovalevskaya top from lgi's numerical tori (docs/quantum.md §10).
// At ℓ = mħ the torus through (h, k) (kovalevskaya_torus.hpp) is written in its
// libration basis (both cycles of Maslov index 2, both frequencies positive, the
// slower first), and (h, k) is moved by a chord Newton method (Jacobian by finite
// differences) until
//   I_slow = ħ(n_slow + ½),  I_fast = ħ(n_fast + ½)
// (J. B. Keller, Ann. Phys. 4 (1958) 180; I. C. Percival, Adv. Chem. Phys. 36 (1977) 1).
// Only the region of the hanging equilibrium is covered, where such a basis exists:
// its tori are the continuation of the two small oscillations.
#include <atomic>
#include <limits>
#include <string>
#include <vector>

#include "experiments/analysis/actions.hpp"
#include "experiments/analysis/quantum/ebk_lagrange.hpp"
#include "experiments/analysis/quantum/quantum_spectrum.hpp"
#include "integrators/system/scene.hpp"

namespace lgi::experiments::quantum {

struct KovalevskayaEbkOptions {
  NumericalTorusOptions torus;  // scheme and step of the tori (dt: the scene's, else 0.01)
  int maslov_returns = 100;     // section returns of the flow for the Maslov index of cycle b
  int max_iterations = 10;      // Newton steps
  double tolerance = 1e-6;      // on max |I − ħ(n + ½)|/ħ
  const std::atomic<bool>* stop = nullptr;  // Ctrl-C: read before every torus; then SolveInterrupted (lowest_levels.hpp)
  KovalevskayaEbkOptions() { torus.crossings = 200, torus.harmonics = 64; }
};

struct KovalevskayaEbkLevel {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  int n_slow = 0, n_fast = 0;
  double energy = nan, k = nan;  // the EBK level and its k = K/c²
  double residual = nan;         // max |I − ħ(n + ½)|/ħ at the last torus
  int mu_a = 0, mu_b = 0;        // the Maslov indices of the last torus's own cycles a, b
  int tori = 0;                  // numerical tori computed
  bool ok = false;
  std::string status;
};

/// Whether the scene is a Kovalevskaya top (gravity only, J = J3 diag(2, 2, 1), centre of mass on e1).
bool is_kovalevskaya_scene(const system::Scene& scene);

/// The EBK level (n_slow, n_fast) at ℓ = l of a Kovalevskaya scene (heavy top, J = J3 diag(2, 2, 1),
/// centre of mass on e1), started from the harmonic estimate about the hanging position.
KovalevskayaEbkLevel kovalevskaya_ebk_level(const system::Scene& scene, double hbar, double l, int n_slow,
                                            int n_fast, const KovalevskayaEbkOptions& options);

/// The symmetry class (QuantumSpectrum::parity_classes) of the level (n_slow, n_fast) of a
/// Kovalevskaya spectrum: C₂ about the centre-of-mass axis is (−1)^(n_slow + n_fast + m), and at
/// m = 0 the reflection U is (−1)^n of the mode whose Γ moves along the frame's axis 2.
int kovalevskaya_ebk_class(const QuantumSpectrum& spectrum, int m, int n_slow, int n_fast);

/// The EBK level of every level of a Kovalevskaya spectrum, in its order: the levels (n_slow, n_fast)
/// whose harmonic estimate lies below the highest level + ħω_slow are solved, and within each
/// symmetry class the i-th EBK level is set beside the i-th exact level (NaN where none is left or
/// its solve failed; n = n_slow, n_fast in the row). `solved` receives every level solved.
std::vector<EbkRow> ebk_kovalevskaya_table(const system::Scene& scene, const QuantumSpectrum& spectrum, double hbar,
                                           int m, const KovalevskayaEbkOptions& options,
                                           std::vector<KovalevskayaEbkLevel>* solved = nullptr);

}  // namespace lgi::experiments::quantum

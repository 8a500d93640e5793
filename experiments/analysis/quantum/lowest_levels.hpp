#pragma once
// The lowest eigenvalues of a Hermitian sparse matrix (lgi quantum's blocks):
// dense (Eigen's SelfAdjointEigenSolver, every eigenvalue) up to
// dense_limit rows; above it Spectra's shift-and-invert Lanczos
// (SymEigsShiftSolver) with the shift below a known lower bound of the
// spectrum, so that the largest eigenvalues of (Ĥ − σ)⁻¹ are the lowest of Ĥ.
// A complex Ĥ = A + iB goes through its real symmetric form [[A, −B], [B, A]]
// (Spectra 1.0 has no Hermitian solver), whose eigenvalues are Ĥ's, each twice;
// the copies are told apart by their eigenvectors (docs/quantum.md §5).
#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

#include "experiments/analysis/quantum/rotor_operators.hpp"

namespace lgi::experiments::quantum {

constexpr Eigen::Index dense_limit = 400;

struct LowestLevels {
  std::vector<double> values;  // ascending
  std::string method;          // "dense", "spectra shift-invert (real)", ...
};

/// A solve ended because `stop` was set (lgi quantum's Ctrl-C).
class SolveInterrupted : public std::runtime_error {
 public:
  SolveInterrupted() : std::runtime_error("quantum: interrupted by signal") {}
};

/// The lowest min(n, size) eigenvalues of the Hermitian `h` (its imaginary
/// part exactly zero when `real`), every eigenvalue ≥ lower_bound.
/// Throws std::runtime_error if Spectra does not converge, SolveInterrupted
/// if `stop` is set: it is read before and after the solve and before every
/// product of the Lanczos iteration (a sparse solve with the factors, ms); the
/// sparse LU factorisation before them and a dense solve cannot be polled
/// (experiments/QUANTUM.md, "Run time" says how long they take).
LowestLevels lowest_levels(const ComplexSparse& h, Eigen::Index n, double lower_bound,
                           const std::atomic<bool>* stop = nullptr);

/// Every eigenvalue of a small Hermitian matrix, ascending (dense).
std::vector<double> all_levels(const ComplexSparse& h);

}  // namespace lgi::experiments::quantum

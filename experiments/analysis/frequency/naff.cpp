// NAFF (naff.hpp): frequencies one at a time, amplitudes by the windowed
// least-squares projection on all terms found (the Gram–Schmidt of Laskar 1990).
#include "experiments/analysis/frequency/naff.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "experiments/analysis/frequency/peak_search.hpp"
#include "experiments/analysis/frequency/windowed_sums.hpp"

namespace lgi::experiments::frequency {
namespace {

/// The basis functions e^{iν_j τ} found so far, their Gram matrix ⟨e_l, e_j⟩ and ⟨f, e_j⟩.
class Basis {
 public:
  explicit Basis(const WindowedGrid& grid, const std::vector<Complex>& f) : grid_(grid), f_(f) {}

  void add(double nu) {
    const Eigen::Index k = static_cast<Eigen::Index>(nu_.size());
    nu_.push_back(nu);
    gram_.conservativeResize(k + 1, k + 1);
    rhs_.conservativeResize(k + 1);
    for (Eigen::Index j = 0; j <= k; ++j) {
      // ⟨e_k, e_j⟩ = Σ ω_i e^{i(ν_k − ν_j)τ_i} = conj(window_sums(ν_k − ν_j)).
      gram_(j, k) = std::conj(window_sums(grid_, nu - nu_[static_cast<std::size_t>(j)]).value);
      gram_(k, j) = std::conj(gram_(j, k));
    }
    rhs_(k) = projection_sums(grid_, f_, nu).value;  // ⟨f, e_k⟩
  }

  /// The coefficients of the projection of f on the span.
  Eigen::VectorXcd coefficients() const { return gram_.colPivHouseholderQr().solve(rhs_); }

  /// f minus its projection on the span.
  std::vector<Complex> residual(const Eigen::VectorXcd& c) const {
    std::vector<Complex> r = f_;
    for (std::size_t j = 0; j < nu_.size(); ++j)
      add_exponential(grid_, -c(static_cast<Eigen::Index>(j)), nu_[j], r);
    return r;
  }

  double frequency(std::size_t j) const { return nu_[j]; }
  std::size_t size() const { return nu_.size(); }

 private:
  const WindowedGrid& grid_;
  const std::vector<Complex>& f_;
  std::vector<double> nu_;
  Eigen::MatrixXcd gram_;
  Eigen::VectorXcd rhs_;
};

void check(std::size_t n, double dt, const NaffOptions& o) {
  if (n < 16) throw std::invalid_argument("naff: fewer than 16 samples");
  if (!(dt > 0.0) || !std::isfinite(dt)) throw std::invalid_argument("naff: the sample spacing must be positive");
  if (o.terms < 1) throw std::invalid_argument("naff: terms must be at least 1");
  if (o.window_order < 0 || o.window_order > 8) throw std::invalid_argument("naff: window order must be 0 to 8");
}

/// A coefficient of e^{iντ} (centred time) referred to the first sample: a e^{iντ} = a e^{−iν T/2} e^{iν(t − t0)}.
Complex at_first_sample(const WindowedGrid& grid, Complex a, double nu) {
  return a * std::polar(1.0, -nu * grid.half_span());
}

NaffResult analyse(const std::vector<Complex>& f, double dt, const NaffOptions& o, bool real_signal) {
  check(f.size(), dt, o);
  WindowedGrid grid = windowed_grid(f.size(), dt, o.window_order);
  grid.stop = o.stop;
  Basis basis(grid, f);
  if (real_signal) basis.add(0.0);  // the constant first, so that its window lobe is never taken for a term
  std::vector<Complex> r = real_signal ? basis.residual(basis.coefficients()) : f;
  std::vector<double> found;
  const double resolution = 1e-3 * std::numbers::pi / grid.half_span();
  double f_power = 0.0;
  for (std::size_t i = 0; i < f.size(); ++i) f_power += grid.weight[i] * std::norm(f[i]);
  for (int k = 0; k < o.terms; ++k) {
    const double omega = strongest_frequency(grid, r, real_signal);
    // Stop where the residual is exhausted (rounding level) or the peak repeats a term found.
    if (!(projection_power(grid, r, omega, real_signal) > 1e-26 * f_power)) break;
    if (std::any_of(found.begin(), found.end(), [&](double w) { return std::abs(w - omega) < resolution; })) break;
    found.push_back(omega);
    basis.add(omega);
    if (real_signal) basis.add(-omega);
    r = basis.residual(basis.coefficients());
  }
  const Eigen::VectorXcd c = basis.coefficients();
  NaffResult result;
  std::size_t j = 0;
  if (real_signal) result.mean = c(0), j = 1;
  for (; j < basis.size(); j += real_signal ? 2 : 1) {
    const double nu = basis.frequency(j);
    const Complex a = at_first_sample(grid, c(static_cast<Eigen::Index>(j)), nu);
    NaffTerm t{nu, std::abs(a), std::arg(a)};
    if (real_signal) {  // a e^{iνt} + a' e^{−iνt} with a' = conj(a) for a real f: A cos(νt + φ), A = |a| + |a'|
      const Complex a_minus = at_first_sample(grid, c(static_cast<Eigen::Index>(j + 1)), -nu);
      t.amplitude = std::abs(a) + std::abs(a_minus);
      t.phase = std::arg(a + std::conj(a_minus));
    }
    result.terms.push_back(t);
  }
  std::stable_sort(result.terms.begin(), result.terms.end(),
                   [](const NaffTerm& x, const NaffTerm& y) { return x.amplitude > y.amplitude; });
  return result;
}

}  // namespace

NaffResult naff_real(const std::vector<double>& f, double dt, const NaffOptions& options) {
  return analyse(std::vector<Complex>(f.begin(), f.end()), dt, options, true);
}

NaffResult naff_complex(const std::vector<std::complex<double>>& f, double dt, const NaffOptions& options) {
  return analyse(f, dt, options, false);
}

}  // namespace lgi::experiments::frequency

// The /ebk and /statistics groups of lgi quantum (quantum_outputs.hpp).
#include "experiments/commands/quantum_outputs.hpp"

#include <cmath>
#include <limits>

#include "experiments/analysis/quantum/ebk_free_rotor.hpp"
#include "experiments/analysis/quantum/ebk_kovalevskaya.hpp"
#include "experiments/analysis/quantum/lowest_levels.hpp"  // SolveInterrupted
#include "experiments/analysis/quantum/quantum_statistics.hpp"
#include "experiments/analysis/quantum/weyl_law.hpp"
#include "experiments/analysis/spectral/brody_fit.hpp"
#include "experiments/analysis/spectral/reference_curves.hpp"
#include "experiments/io/number_format.hpp"

namespace lgi::experiments {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TableColumn real_column(const std::string& name, std::vector<double> values, int width = 1) {
  return {name, width, false, std::move(values), {}};
}
TableColumn whole_column(const std::string& name, std::vector<std::int64_t> values) {
  return {name, 1, true, {}, std::move(values)};
}

}  // namespace

TableGroup ebk_group(const quantum::QuantumSpectrum& q, double hbar, int m, const system::Scene* kovalevskaya,
                     std::vector<std::string>* notes, const std::atomic<bool>* stop) {
  std::vector<std::int64_t> n, ms, k, js, axes, converged, n_fast;
  std::vector<double> ebk, exact, difference;
  std::vector<quantum::EbkRow> rows;
  if (kovalevskaya) {
    quantum::KovalevskayaEbkOptions options;
    options.torus.dt = kovalevskaya->dt.value_or(1e-2);
    options.stop = stop;
    std::vector<quantum::KovalevskayaEbkLevel> solved;
    rows = quantum::ebk_kovalevskaya_table(*kovalevskaya, q, hbar, m, options, &solved);
    for (const auto& s : solved)
      if (notes)
        notes->push_back("EBK (n_slow, n_fast) = (" + std::to_string(s.n_slow) + ", " + std::to_string(s.n_fast) +
                         "): E = " + format_general(s.energy, 12) + ", k = " + format_general(s.k, 8) +
                         ", Maslov (a, b) = (" + std::to_string(s.mu_a) + ", " + std::to_string(s.mu_b) +
                         "), residual " + format_general(s.residual, 3) + ", " + std::to_string(s.tori) + " tori, " +
                         s.status);
  } else {
    rows = quantum::ebk_table(q, hbar, m);
  }
  for (const quantum::EbkRow& r : rows) {
    n.push_back(r.n), ms.push_back(r.m), k.push_back(r.k), js.push_back(r.j), axes.push_back(r.axis);
    n_fast.push_back(r.n_fast);
    converged.push_back(r.converged ? 1 : 0);
    ebk.push_back(r.energy_ebk), exact.push_back(r.energy_exact), difference.push_back(r.energy_ebk - r.energy_exact);
  }
  const char* rule =
      kovalevskaya
          ? "the numerical torus in its libration basis (both Maslov indices 2, from the tangent planes span(X_H, X_K)): "
            "I_slow = hbar (n + 1/2), I_fast = hbar (n_fast + 1/2); within each parity class the i-th EBK level "
            "beside the i-th exact level (docs/quantum.md section 10)"
      : q.top.is_free()
          ? "|L| = hbar (j + 1/2); the cap of the orbit of Pi about its axis: I_cap = hbar (n + 1/2), Maslov index 2 "
            "(Colwell, Handy & Miller 1977); n counts the doublets from the steady rotation (docs/quantum.md "
            "section 9)"
          : "I_theta(E; l = m hbar, L3 = k hbar) = hbar (n + 1/2), Maslov index 2 (Keller 1958); n = the level's "
            "rank in its k block (docs/quantum.md section 7)";
  return {"ebk",
          {whole_column("n", n), whole_column("m", ms), whole_column("k", k), real_column("energy_ebk", ebk),
           real_column("energy_exact", exact), real_column("difference", difference),
           whole_column("converged", converged), whole_column("j", js), whole_column("axis", axes),
           whole_column("n_fast", n_fast)},
          {{"rule", rule}}};
}

TableGroup weyl_group(const quantum::QuantumSpectrum& q, double hbar, int m, const std::atomic<bool>* stop) {
  std::vector<double> count;
  const auto poll = [stop] {
    if (stop != nullptr && stop->load(std::memory_order_relaxed)) throw quantum::SolveInterrupted();
  };
  if (q.top.is_free()) {
    for (const quantum::QuantumLevel& l : q.levels) {
      poll();
      count.push_back(quantum::free_rotor_weyl_count(q.top.moments, hbar, l.j, l.energy));
    }
  } else {
    const quantum::WeylCounting weyl(q.top, hbar, m);
    for (const quantum::QuantumLevel& l : q.levels) {
      poll();
      count.push_back(weyl(l.energy));
    }
  }
  return {"weyl",
          {real_column("weyl_count", count)},
          {{"meaning", "one row per /spectrum row: the smooth count of levels below its energy at this m, "
                       "Vol{H <= E}/(2 pi hbar)^2 (a free body: N_j(E) of its j); docs/quantum.md section 8"}}};
}

TableGroup statistics_group(const quantum::QuantumSpectrum& q, double hbar, int m, double energy_low,
                            double energy_high, const std::atomic<bool>* stop) {
  const spectral::StatisticsOptions options;
  const auto classes = quantum::quantum_statistics(q, hbar, m, options, energy_low, energy_high, stop);
  const quantum::PooledBrody pooled = quantum::pooled_brody(classes);
  const std::size_t bins = static_cast<std::size_t>(std::lround(options.s_max / options.bin_width));
  const std::size_t nl = options.lengths.size();
  std::vector<std::int64_t> j, parity, levels, bound;
  std::vector<double> beta, beta_error, density, density_error, sigma2, sigma2_error, delta3, delta3_error;
  for (const auto& c : classes) {
    const spectral::SpectralStatistics& s = c.statistics.statistics;
    j.push_back(c.j), parity.push_back(c.parity), levels.push_back(static_cast<std::int64_t>(s.levels));
    const bool empty = c.statistics.too_few;
    beta.push_back(empty ? kNaN : s.brody.beta), beta_error.push_back(empty ? kNaN : s.brody.standard_error);
    bound.push_back(empty ? 0 : s.brody.bound);
    for (std::size_t b = 0; b < bins; ++b) {
      const bool held = !empty && b < s.histogram.density.size();
      density.push_back(held ? s.histogram.density[b] : kNaN);
      density_error.push_back(held ? s.histogram.density_error[b] : kNaN);
    }
    for (std::size_t i = 0; i < nl; ++i) {
      sigma2.push_back(empty ? kNaN : s.number_variance[i].value);
      sigma2_error.push_back(empty ? kNaN : s.number_variance[i].standard_error);
      delta3.push_back(empty ? kNaN : s.rigidity[i].value);
      delta3_error.push_back(empty ? kNaN : s.rigidity[i].standard_error);
    }
  }
  std::vector<double> centres, poisson_p, wigner_p, gue_p, poisson_s2, goe_s2, gue_s2, poisson_d3, goe_d3, gue_d3;
  for (std::size_t b = 0; b < bins; ++b) {
    const double s = (static_cast<double>(b) + 0.5) * options.bin_width;
    centres.push_back(s), poisson_p.push_back(spectral::poisson_spacing_density(s));
    wigner_p.push_back(spectral::wigner_spacing_density(s)), gue_p.push_back(spectral::gue_spacing_density(s));
  }
  for (double L : options.lengths) {
    poisson_s2.push_back(spectral::poisson_number_variance(L)), goe_s2.push_back(spectral::goe_number_variance(L));
    poisson_d3.push_back(spectral::poisson_rigidity(L)), goe_d3.push_back(spectral::goe_rigidity(L));
    gue_s2.push_back(spectral::gue_number_variance(L)), gue_d3.push_back(spectral::gue_rigidity(L));
  }
  const int wb = static_cast<int>(bins), wl = static_cast<int>(nl);
  return {"statistics",
          {whole_column("j", j), whole_column("parity", parity), whole_column("levels", levels),
           real_column("brody_beta", beta), real_column("brody_error", beta_error), whole_column("brody_bound", bound),
           real_column("spacing_density", density, wb), real_column("spacing_density_error", density_error, wb),
           real_column("number_variance", sigma2, wl), real_column("number_variance_error", sigma2_error, wl),
           real_column("rigidity", delta3, wl), real_column("rigidity_error", delta3_error, wl),
           real_column("bin_centre", centres), real_column("poisson_density", poisson_p),
           real_column("wigner_density", wigner_p), real_column("gue_density", gue_p),
           real_column("length", options.lengths),
           real_column("poisson_number_variance", poisson_s2), real_column("goe_number_variance", goe_s2),
           real_column("poisson_rigidity", poisson_d3), real_column("goe_rigidity", goe_d3),
           real_column("gue_number_variance", gue_s2), real_column("gue_rigidity", gue_d3)},
          {{"unfolding", "Weyl's law (docs/quantum.md section 8): per class N(E)/classes; a free body per j "
                         "and D2 class N_j(E)/4"},
           {"levels_used", "converged levels with energy_low <= E <= energy_high only; a symmetric heavy top at "
                           "m = 0: k >= 0 only"},
           {"energy_low", format_general(energy_low, 17)}, {"energy_high", format_general(energy_high, 17)},
           {"pooled_spacings", std::to_string(pooled.spacings)},
           {"pooled_brody_beta", format_general(pooled.fit.beta, 6)},
           {"pooled_brody_error", format_general(pooled.fit.standard_error, 6)}}};
}

}  // namespace lgi::experiments

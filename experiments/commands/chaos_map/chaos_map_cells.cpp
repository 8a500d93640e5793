#include "experiments/commands/chaos_map/chaos_map_cells.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "experiments/analysis/binomial_interval.hpp"
#include "experiments/io/number_format.hpp"

namespace lgi::experiments {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  const std::size_t m = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(m), v.end());
  const double upper = v[m];
  if (v.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(m)));
}

}  // namespace

ChaosCellColumns::ChaosCellColumns(int width)
    : c_{{"status", width, true},          {"orbits", width, true},         {"chaotic", width, true},
         {"chaotic_fraction", width},      {"chaotic_fraction_low", width}, {"chaotic_fraction_high", width},
         {"megno_median", width},          {"lyapunov_max", width},         {"lyapunov_median", width}} {}

void ChaosCellColumns::add(std::int64_t status, const std::vector<double>& megno, const std::vector<double>& lyapunov,
                           double threshold) {
  const bool any = status == cell_ok && !megno.empty();
  std::int64_t chaotic = 0;
  for (const double y : megno) chaotic += y > threshold ? 1 : 0;
  const BinomialInterval w = any ? wilson_interval(chaotic, static_cast<std::int64_t>(megno.size())) : BinomialInterval{};
  c_[0].whole.push_back(status);
  c_[1].whole.push_back(static_cast<std::int64_t>(megno.size()));
  c_[2].whole.push_back(any ? chaotic : 0);
  c_[3].real.push_back(w.fraction), c_[4].real.push_back(w.low), c_[5].real.push_back(w.high);
  c_[6].real.push_back(any ? median(megno) : NAN);
  c_[7].real.push_back(any ? *std::max_element(lyapunov.begin(), lyapunov.end()) : NAN);
  c_[8].real.push_back(any ? median(lyapunov) : NAN);
}

std::vector<TableColumn> ChaosCellColumns::columns() const { return c_; }

void add_chaos_map_attributes(TableGroup& map, double threshold, const std::string& measure,
                              const std::string& empty_reason, const std::string& unreached_reason) {
  map.attributes["status_names"] = "0: ok\n1: " + empty_reason + "\n2: " + unreached_reason + "\n3: not run (interrupted)";
  map.attributes["threshold"] = exact_number(threshold);
  map.attributes["measure"] = measure;
  map.attributes["interval"] = "chaotic_fraction_low, chaotic_fraction_high: the 95 % Wilson score interval of "
                               "chaotic / orbits as an estimate of the phase-space fraction of the level set";
}

std::string exact_number(double x) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", x);
  return b;
}

void print_chaos_fractions(const TableGroup& map, const std::string& axis_column, const std::string& axis_label) {
  const auto column = [&](const std::string& name) -> const TableColumn& {
    return *std::find_if(map.columns.begin(), map.columns.end(), [&](const TableColumn& c) { return c.name == name; });
  };
  const TableColumn &axis = column(axis_column), &hs = column("h"), &status = column("status"),
                    &orbits = column("orbits"), &chaotic = column("chaotic");
  const std::size_t nh = hs.real.size();
  for (std::size_t c = 0; c < status.whole.size(); ++c) {
    if (status.whole[c] != cell_ok || orbits.whole[c] == 0) continue;
    std::cout << "  " << axis_label << " = " << format_general(axis.real[c / nh]) << ", h = "
              << format_general(hs.real[c % nh]) << ": chaotic " << format_fraction(chaotic.whole[c], orbits.whole[c])
              << '\n';
  }
}

}  // namespace lgi::experiments

#pragma once
// The per-cell columns of /chaos_map (experiments/CHAOS_MAP.md, "Output"),
// shared by the (l, h) maps of heavy tops and the (key, h) maps of Cardan
// tops: status, orbit and chaotic counts, the chaotic fraction with its 95 %
// Wilson interval, the median MEGNO and the largest and median λ.
#include <cstdint>
#include <string>
#include <vector>

#include "experiments/io/table_file.hpp"

namespace lgi::experiments {

enum ChaosCellStatus : std::int64_t { cell_ok = 0, cell_empty = 1, cell_unreached = 2, cell_not_run = 3 };

class ChaosCellColumns {
 public:
  /// `width`: cells per row of the grid (the h axis).
  explicit ChaosCellColumns(int width);
  /// One cell: its status and the indicators of its orbits with finite values.
  void add(std::int64_t status, const std::vector<double>& megno, const std::vector<double>& lyapunov,
           double threshold);
  /// status, orbits, chaotic, chaotic_fraction, _low, _high, megno_median, lyapunov_max, lyapunov_median.
  std::vector<TableColumn> columns() const;

 private:
  std::vector<TableColumn> c_;
};

/// The group attributes of /chaos_map: status_names (with `empty_reason`
/// for status 1 and `unreached_reason` for 2), threshold, measure, interval.
void add_chaos_map_attributes(TableGroup& map, double threshold, const std::string& measure,
                              const std::string& empty_reason, const std::string& unreached_reason);

/// "%.17g": a number as the command line and /parameters give it.
std::string exact_number(double x);

/// One line per computed cell: "<axis> = x, h = y: chaotic k/n = f [low, high]".
void print_chaos_fractions(const TableGroup& map, const std::string& axis_column, const std::string& axis_label);

}  // namespace lgi::experiments

#pragma once
// What the stress command writes and prints: the criterion in words, the
// /results columns and rows, the /case_NN attributes, and the tallies of
// the summary table.
#include <map>
#include <string>
#include <vector>

#include "experiments/commands/stress/stress_runner.hpp"
#include "experiments/io/results_file.hpp"

namespace lgi::experiments::stress {

std::string criterion_text(const Criterion& c);
std::vector<Column> result_columns();
void append_row(ResultsFile& file, const Row& r, const Variant& v);
/// /case_NN: one group per variant with what it runs, its reference and its criterion.
ResultAttributes case_attributes(const Variant& v);

/// Counts of outcomes and passes, for a case or the whole suite.
struct Tally {
  int runs = 0, ok = 0, refused = 0, failed = 0, pass = 0, wrong = 0;
  std::map<std::string, int> not_passed;  // scheme -> rows
};

/// The tallies per case, in the order the cases first appear, and the total.
struct Summary {
  std::map<std::string, Tally> by_case;
  std::vector<std::string> order;
  Tally total;
};
Summary summarise(const std::vector<Row>& rows);

/// /diagnostics of a stress file.
ResultAttributes summary_attributes(const Summary& s, const std::string& status, double cpu_seconds,
                                    std::size_t rows);

/// The table printed on stdout (runs, outcomes, passes per case).
std::string summary_table(const Summary& s);

}  // namespace lgi::experiments::stress

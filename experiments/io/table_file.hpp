#pragma once
// A finished table written at once: /<group>/<column> datasets (n, or n×k
// for vector columns; float64 or int64; or text: n variable-length strings) with /parameters attributes (and
// libm, libm_code_path.hpp, unless the caller gave it), and the
// same table as CSV beside it (vector columns as <name>_1, <name>_2, ...).
// For results computed in full before they are written (lgi equilibria,
// lgi region, lgi chaos-map);
// tables that grow while a run goes on use ResultsFile (results_file.hpp).
// The file is written as <path>.partial and renamed; an existing file is
// replaced only with `force`.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace lgi::experiments {

struct TableColumn {
  std::string name;
  int width = 1;
  bool integer = false;
  std::vector<double> real{};         // rows × width
  std::vector<std::int64_t> whole{};  // rows × width, for integer columns
  std::vector<std::string> text{};    // rows, for a text column (width 1; a UTF-8 string dataset)
  bool is_text = false;
};

/// A group of columns in a file of several groups: each column has its own
/// number of rows (values / width), e.g. a grid's axes beside its values;
/// `attributes` become string attributes of the group.
struct TableGroup {
  std::string name;
  std::vector<TableColumn> columns{};
  std::map<std::string, std::string> attributes{};
};

/// `extra_groups` are written into the same HDF5 file after /<group> (not into the CSV).
void write_table_file(const std::string& path, bool force, const std::string& group,
                      const std::vector<TableColumn>& columns, const std::map<std::string, std::string>& parameters,
                      const std::vector<TableGroup>& extra_groups = {});

/// Several groups and /parameters in one HDF5 file, no CSV (lgi region, lgi
/// chaos-map): written as <path>.partial and renamed; `force` as above.
void write_groups_file(const std::string& path, bool force, const std::vector<TableGroup>& groups,
                       const std::map<std::string, std::string>& parameters);

}  // namespace lgi::experiments

#pragma once
// The open files of a ResultsFile (results_file.hpp), shared by
// results_file.cpp (a new file) and results_file_resume.cpp (a file reopened
// to resume a run); internal to io/.
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "experiments/io/hdf5_support.hpp"
#include "experiments/io/results_file.hpp"

namespace lgi::experiments {

namespace results_detail {

inline bool valid_name(const std::string& n) {
  return !n.empty() && n != "." && n != ".." && n.find('/') == std::string::npos;
}

/// Checks the column and table names and the options; fills `index` (name -> column).
inline void index_columns(const std::vector<Column>& columns, const ResultsFileOptions& options,
                   std::map<std::string, std::size_t>& index) {
  if (columns.empty()) throw std::invalid_argument("results table: no columns");
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (!valid_name(columns[i].name))
      throw std::invalid_argument("results table: bad column name '" + columns[i].name + "'");
    if (!index.emplace(columns[i].name, i).second)
      throw std::invalid_argument("results table: column '" + columns[i].name + "' given twice");
  }
  if (!valid_name(options.table) || options.table == "h5md" || options.table == "parameters" ||
      options.table == "diagnostics")
    throw std::invalid_argument("results table: bad table name '" + options.table + "'");
  if (options.block_rows == 0 || options.chunk_rows == 0)
    throw std::invalid_argument("results file: block_rows and chunk_rows must be positive");
}

}  // namespace results_detail

struct ResultsFile::Impl {
  // Declaration order: datasets close before groups, groups before the file.
  hdf5::Handle file;
  hdf5::Handle table;
  hdf5::Handle diagnostics;
  std::vector<hdf5::Handle> columns;
  hdf5::Handle string_type;
  std::FILE* csv = nullptr;
  ~Impl() {
    columns.clear();
    diagnostics.reset();
    table.reset();
    file.reset();
    if (csv) std::fclose(csv);
  }
};

}  // namespace lgi::experiments

#pragma once
// The open files of a ResultsFile (results_file.hpp), shared by
// results_file.cpp (a new file) and results_file_resume.cpp (a file reopened
// to resume a run); internal to io/.
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "experiments/io/fnv_hash.hpp"
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

/// The checksum of a row (results_file.hpp, "Row checksums"): FNV-1a over its cells as stored
/// (8 bytes a number; a text's bytes and a NUL) and then its CSV line, '\n' included.
inline std::uint64_t row_hash(const std::vector<ResultRow::Cell>& cells, std::string_view csv_line) {
  Fnv1a h;
  for (const auto& cell : cells) {
    if (const double* x = std::get_if<double>(&cell)) h.value(*x);
    else if (const std::int64_t* k = std::get_if<std::int64_t>(&cell)) h.value(*k);
    else {
      const std::string& t = std::get<std::string>(cell);
      h.bytes(t.c_str(), t.size() + 1);
    }
  }
  h.bytes(csv_line.data(), csv_line.size());
  return h.get();
}

}  // namespace results_detail

struct ResultsFile::Impl {
  // Declaration order: datasets close before groups, groups before the file.
  hdf5::Handle file;
  hdf5::Handle table;
  hdf5::Handle diagnostics;
  std::vector<hdf5::Handle> columns;
  hdf5::Handle row_hashes;  // /<group>/row_hash, if the file keeps row checksums
  hdf5::Handle string_type;
  std::FILE* csv = nullptr;
  ~Impl() {
    columns.clear();
    row_hashes.reset();
    diagnostics.reset();
    table.reset();
    file.reset();
    if (csv) std::fclose(csv);
  }
};

}  // namespace lgi::experiments

#pragma once
// Result files of the experiment subcommands (work-precision, long-time,
// stress; layout: experiments/RESULTS.md). One HDF5 file (C API) with
//   /h5md         version, author, creator, modules/units (as trajectory files)
//   /parameters   attributes: the subcommand's settings plus compiler,
//                 cxx_flags, build_type, hdf5_version, utc_start
//   /<table>      ("results" or "series") one 1-D dataset per column, one
//                 element per row: float64, int64 or variable-length UTF-8
//   /diagnostics  attributes; status "running" until finish/abandon
// and, beside it, a CSV file with the same table (header row, one row per
// table row): <out>.csv, where <out> is the HDF5 name without its ".h5" /
// ".hdf5" suffix (results_csv_path()).
//
// Life of a file (the rules of trajectory files, OUTPUT.md):
//   ResultsFile f(path, force, columns, options);   // refuses an existing path or CSV unless force;
//                                                    // creates <path>.partial and <csv>.partial
//   f.write_parameters(attrs); f.write_group("reference", attrs);
//   f.append(row); ...           // buffered; written in blocks (one H5Dwrite per column) + H5Fflush
//   f.finish(diagnostics);       // writes what is buffered, closes, renames both .partial files
// or f.abandon(diagnostics with status = the reason): both files stay as
// .partial, readable, with every row appended. A ResultsFile destroyed
// without either abandons with status "interrupted". A process killed
// outright leaves readable .partial files up to the last flush, status
// "running".
//
// Resume (lgi long-time --resume): ResultsFile(path, force, columns, options,
// ResultsFile::Reopen{}) opens the .partial files an interrupted run left,
// checks that they hold this table (every column with its type, the CSV
// header), and keep_rows(n) drops what came after the run's last checkpoint;
// appending then goes on. A run's checkpoint is a fixed-size record
// (create_record / write_record / read_record), written in place: its
// writes change raw data only, never the file's metadata.
//
// Row checksums (lgi long-time; RESULTS.md, "long-time --resume"):
// keep_row_hashes(group) makes the file keep, in the extendible dataset
// /<group>/row_hash, one FNV-1a hash per row over its cells as stored and its
// CSV line (results_file_impl.hpp, row_hash), written with the row.
// Reopened, reopen_row_hashes(group) finds them and first_damaged_row(n)
// checks rows 0..n-1 of both files against them before the run goes on.
//
// Every failure to create, write or publish throws OutputFileError (declared
// in h5md_writer.hpp) with one line naming the file; a write that fails once
// the files exist throws OutputWriteError (the commands exit 1 on it). A
// ResultsFile destroyed after such a failure abandons with status "failed: <why>".
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "experiments/io/h5md_writer.hpp"  // OutputFileError, Diagnostics, hdf5_library_version

namespace lgi::experiments {

enum class ColumnType { real, integer, text };

struct Column {
  std::string name;
  ColumnType type = ColumnType::real;
  std::string unit;  // H5MD units spelling; empty: no unit attribute
};

/// Attributes of a group. Text: scalar variable-length UTF-8 strings;
/// numbers float64; integers int64; arrays 1-D float64.
struct ResultAttributes {
  std::map<std::string, std::string> text;
  std::map<std::string, std::string> fixed_text;  // fixed-length strings: what a resume reads back (hdf5_support.hpp)
  std::map<std::string, double> number;
  std::map<std::string, std::int64_t> integer;
  std::map<std::string, std::vector<double>> number_array;
};

/// /diagnostics attributes of a Diagnostics record (OUTPUT.md).
ResultAttributes diagnostics_attributes(const Diagnostics& d);

/// "<out>.csv" beside "<out>.h5" (or "<out>.hdf5"); "<path>.csv" otherwise.
std::string results_csv_path(const std::string& h5_path);

struct ResultsFileOptions {
  std::string table = "results";       // the table's group: "results" or "series"
  std::size_t block_rows = 256;         // rows buffered between writes (>= 1)
  std::size_t chunk_rows = 256;         // HDF5 chunk length (>= 1)
  double flush_interval_seconds = 2.0;  // append() and flush_if_due() flush at least this often
};

/// One row, by column name. Cells not set hold NaN, -1 or "" (RESULTS.md).
class ResultRow {
 public:
  using Cell = std::variant<double, std::int64_t, std::string>;
  void set(const std::string& column, double value);
  void set(const std::string& column, std::int64_t value);
  void set(const std::string& column, int value) { set(column, static_cast<std::int64_t>(value)); }
  void set(const std::string& column, const std::string& value);
  void set(const std::string& column, const char* value) { set(column, std::string(value)); }
  const std::vector<Cell>& cells() const { return cells_; }

 private:
  friend class ResultsFile;
  std::size_t index(const std::string& column, ColumnType type) const;
  const std::vector<Column>* columns_ = nullptr;
  const std::map<std::string, std::size_t>* index_ = nullptr;
  std::vector<Cell> cells_;
};

class ResultsFile {
 public:
  /// Refuses (OutputFileError, nothing created) if `path` or its CSV exists
  /// and !force, or if the directory is missing or not writable. Throws
  /// std::invalid_argument for empty, duplicate or malformed column names.
  ResultsFile(const std::string& path, bool force, std::vector<Column> columns, ResultsFileOptions options = {});
  /// Reopens <path>.partial and its CSV twin left by an interrupted run (top
  /// of this file). OutputFileError naming the file and what is wrong if
  /// they are missing, not HDF5, or do not hold this table; rows() is the
  /// number of rows complete in both. Nothing is changed until keep_rows()
  /// (destroyed before it, the files are closed as they were).
  struct Reopen {};
  ResultsFile(const std::string& path, bool force, std::vector<Column> columns, ResultsFileOptions options, Reopen);
  ResultsFile(const ResultsFile&) = delete;
  ResultsFile& operator=(const ResultsFile&) = delete;
  ~ResultsFile();

  /// Attributes of /parameters; compiler, cxx_flags, build_type,
  /// hdf5_version and utc_start are added unless given. Call once.
  void write_parameters(const ResultAttributes& attributes);
  /// Creates (or adds attributes to) the group /<name> with these attributes.
  void write_group(const std::string& name, const ResultAttributes& attributes);

  /// An empty row for this table (every cell missing).
  ResultRow row() const;
  /// Buffers a row; writes the block when it is full or when the flush
  /// interval has passed.
  void append(const ResultRow& row);
  /// Writes the buffered rows (HDF5 and CSV) and flushes both files.
  void flush();
  /// flush() if rows are buffered and the flush interval has passed since the
  /// last flush (reads the clock: call it every few thousand steps, not every step).
  void flush_if_due();

  /// Writes the buffered rows and /diagnostics, closes, renames the .partial
  /// files to their names (without force: refuses if one appeared meanwhile).
  void finish(const ResultAttributes& diagnostics);
  /// Writes the buffered rows and /diagnostics, closes, leaves the .partial
  /// files. A no-op once closed.
  void abandon(const ResultAttributes& diagnostics);

  /// Resume: keeps the first n rows (0 <= n <= rows()) of both files, drops
  /// the others, and sets /diagnostics status back to "running".
  void keep_rows(std::int64_t n);
  /// A scalar fixed-length text attribute of /<group> (ResultAttributes::fixed_text); std::nullopt if
  /// absent, not text or variable-length (never read: hdf5_support.hpp, read_fixed_string_attribute).
  std::optional<std::string> text_attribute(const std::string& group, const std::string& name) const;
  /// A record of `bytes` zero bytes at /<group>/<name> (the group is created if missing).
  void create_record(const std::string& group, const std::string& name, std::size_t bytes);
  /// Writes `data` at `offset` into the record, then flushes the file.
  void write_record(const std::string& group, const std::string& name, std::size_t offset,
                    const std::vector<unsigned char>& data);
  /// Keeps a checksum of every row from now on in /<group>/row_hash (top of this file); before any row.
  void keep_row_hashes(const std::string& group);
  /// Reopen: opens /<group>/row_hash (OutputFileError if it is missing or not one); rows() counts
  /// only the rows that have one.
  void reopen_row_hashes(const std::string& group);
  /// Reopen, after reopen_row_hashes: the first of rows 0..n−1 whose HDF5 cells or CSV line do not
  /// match its checksum; −1 if none. Reads only.
  std::int64_t first_damaged_row(std::int64_t n) const;
  /// The record's bytes; empty if it is absent or not a record (1-D, 8-bit unsigned).
  std::vector<unsigned char> read_record(const std::string& group, const std::string& name) const;

  const std::string& path() const { return path_; }
  const std::string& partial_path() const { return partial_path_; }
  const std::string& csv_path() const { return csv_path_; }
  std::string csv_partial_path() const { return csv_path_ + ".partial"; }
  std::int64_t rows() const { return written_ + static_cast<std::int64_t>(buffer_.size()); }

 private:
  struct Impl;
  void create_csv(const std::string& csv_partial);  // construction: CSV header
  void create_table();                              // construction: one dataset per column
  void reopen_table();                              // Reopen: the columns, checked; rows found
  void reopen_csv(const std::string& csv_partial);  // Reopen: the header, checked; rows counted
  void reopen_for_writing();                        // Reopen, at keep_rows(): read-only until then
  void write_block();
  void write_row_hashes(std::uint64_t at, const std::vector<std::uint64_t>& hashes);
  /// The cells of rows first..first+n−1, read back from the HDF5 table.
  std::vector<std::vector<ResultRow::Cell>> read_cells(std::int64_t first, std::int64_t n) const;
  void write_attributes(std::int64_t group, const ResultAttributes& a);
  void close_files();
  /// Closes what is still open after a failure, keeping quiet about further
  /// errors (the caller rethrows the first one).
  void close_after_failure() noexcept;
  [[noreturn]] void fail(const std::string& what) const;
  [[noreturn]] void fail_csv() const;  // the CSV twin could not be written (errno)

  std::string path_, partial_path_, csv_path_;
  bool force_ = false;
  std::vector<Column> columns_;
  std::map<std::string, std::size_t> index_;
  ResultsFileOptions options_;
  std::unique_ptr<Impl> impl_;
  bool open_ = false;
  bool created_ = false;  // the files exist: failures are OutputWriteError
  bool write_failed_ = false;
  std::string write_error_;  // why (the destructor's status)
  std::vector<ResultRow> buffer_;
  std::int64_t written_ = 0;
  std::chrono::steady_clock::time_point last_flush_{};
  std::vector<long> csv_row_ends_;  // Reopen: byte offset after the header and after each row of the CSV
  bool untouched_ = false;          // Reopen, before keep_rows(): destroyed, it closes and writes nothing
  std::string row_hash_group_;      // the group of /<group>/row_hash, if the file keeps row checksums
};

}  // namespace lgi::experiments

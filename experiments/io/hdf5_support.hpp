#pragma once
// One copy of the HDF5 C-API plumbing behind the trajectory files
// (h5md_writer.cpp), the result files (results_file.cpp) and the singularity
// study (singularity_command.cpp): an owning handle, a quiet error stack,
// attribute and group writers with the exact types the layouts promise
// (OUTPUT.md, RESULTS.md, SINGULARITY.md), the /h5md metadata group, and the
// CSV quoting and no-replace publishing of finished files. Kept in one place
// so the three files cannot drift apart; internal to the experiments library.
#include <hdf5.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace lgi::experiments::hdf5 {

/// Owns an HDF5 identifier and closes it with the matching H5?close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), close_(closer) {}
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, H5I_INVALID_HID)), close_(o.close_) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, H5I_INVALID_HID);
      close_ = o.close_;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  /// Closes now; returns the close status (0 if nothing was open).
  herr_t reset() {
    herr_t r = 0;
    if (id_ >= 0 && close_ != nullptr) r = close_(id_);
    id_ = H5I_INVALID_HID;
    return r;
  }

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer close_ = nullptr;
};

/// HDF5 prints its error stack to stderr by default; the writers report
/// failures through one-line exceptions instead. Silenced while this lives,
/// restored afterwards (the setting is per thread).
class QuietHdf5Errors {
 public:
  QuietHdf5Errors();
  ~QuietHdf5Errors();
  QuietHdf5Errors(const QuietHdf5Errors&) = delete;
  QuietHdf5Errors& operator=(const QuietHdf5Errors&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

/// The innermost description on the current HDF5 error stack, on one line.
std::string hdf5_error_detail();
std::string errno_text(int err);
/// "YYYY-MM-DDTHH:MM:SSZ".
std::string utc_now_iso8601();
/// $USER, else $LOGNAME, else "unknown".
std::string author_name();
/// "." for a bare file name, "/" for a file in the root.
std::string parent_directory(const std::string& path);

/// Called with a short description ("cannot write attribute x") when an HDF5
/// call fails; each file adds its own name and context, and must throw.
using Fail = std::function<void(const std::string& what)>;

Handle scalar_space(const Fail& fail);
/// Variable-length string type, UTF-8 (h5py reads str) unless ascii.
Handle vlen_string_type(bool ascii, const Fail& fail);
/// Writes an attribute, replacing one of that name.
void write_attribute(hid_t obj, const char* name, hid_t file_type, hid_t memory_type, hid_t space, const void* data,
                     const Fail& fail);
/// Scalar variable-length string attribute.
void write_vlen_string(hid_t obj, const char* name, const std::string& value, bool ascii, const Fail& fail);
/// Scalar fixed-length (UTF-8, null-padded) string attribute: for what a
/// resume reads back (read_fixed_string_attribute).
void write_fixed_string(hid_t obj, const char* name, const std::string& value, const Fail& fail);
/// Fixed-length, null-terminated UTF-8 string attributes: scalar for one
/// value, rank 1 for several (H5MD 1.1 asks fixed length for the /h5md
/// metadata and box/boundary).
void write_fixed_strings(hid_t obj, const char* name, const std::vector<std::string>& values, bool scalar,
                         const Fail& fail);
/// Scalar integer attribute of file type `file_type` (H5T_STD_I64LE, H5T_STD_I32LE).
void write_int_attribute(hid_t obj, const char* name, hid_t file_type, std::int64_t value, const Fail& fail);
/// Scalar H5T_IEEE_F64LE attribute.
void write_double_attribute(hid_t obj, const char* name, double value, const Fail& fail);
/// 1-D H5T_IEEE_F64LE attribute; an empty vector gets a null dataspace.
void write_double_array(hid_t obj, const char* name, const std::vector<double>& values, const Fail& fail);

/// A scalar string attribute `name` of obj (variable or fixed length, read
/// with a memory type of HDF5's choosing, never the file's); std::nullopt if
/// it is absent, not a string, not scalar, or unreadable. For files made by
/// others: any bytes in them end here, not in a crash.
std::optional<std::string> read_string_attribute(hid_t obj, const char* name);
/// Only a fixed-length string attribute; std::nullopt for a variable-length
/// one, which is never read. The resume paths use it on the fingerprints
/// lgi writes as fixed-length strings (write_fixed_string): reading a
/// variable-length string goes through HDF5's global heap, and libhdf5 1.10
/// can loop forever on a damaged heap (H5HG_read; fuzz/fuzz_h5_readers.cpp).
std::optional<std::string> read_fixed_string_attribute(hid_t obj, const char* name);
/// The same attribute of the object `object` ("/resume") in the file at
/// `path`, opened read-only (nothing in the file changes); std::nullopt if
/// the file, the object or the attribute is missing or unreadable. Throws
/// nothing; `readable` (if given) says whether the file opened as HDF5.
std::optional<std::string> read_string_attribute(const std::string& path, const std::string& object,
                                                 const char* name, bool* readable = nullptr);
/// The same, fixed-length strings only (read_fixed_string_attribute).
std::optional<std::string> read_fixed_string_attribute(const std::string& path, const std::string& object,
                                                       const char* name, bool* readable = nullptr);

/// Creates the group `path` (absolute, or relative to loc; its parent must exist).
Handle create_group(hid_t loc, const std::string& path, const Fail& fail);
/// Opens the group `name` below parent, creating it if missing.
Handle open_or_create_group(hid_t parent, const std::string& name, const Fail& fail);
/// Creates (truncates) an HDF5 file whose H5Fclose closes every object in it.
/// `sieve_bytes`: HDF5's sieve buffer for raw data (0: each write goes to the
/// file at once, with no read of the region first; the sweep's partial file).
Handle create_file(const std::string& path, const Fail& fail, std::size_t sieve_bytes = 64 * 1024);
/// /h5md as H5MD 1.1 asks: version, author/name, creator/name and version,
/// and with units_module the units module (modules/units: version, system "SI").
void write_h5md_metadata(hid_t file, bool units_module, const Fail& fail);
/// The /parameters text every file carries unless the caller set it, in
/// this order: compiler, cxx_flags, build_type, libm (libm_code_path.hpp),
/// hdf5_version, utc_start.
std::vector<std::pair<std::string, std::string>> default_provenance(const std::string& utc_start);

/// Shortest round-trip form; "nan", "inf", "-inf".
std::string csv_number(double x);
/// Quoted (with doubled quotes) when it holds a comma, quote or line break.
std::string csv_text(const std::string& s);

/// Whether anything (a file, a link, a folder) is at `path`.
bool path_exists(const std::string& path);

/// The one rule for every output lgi writes (README.md, "Outputs"), checked
/// before anything is written and again at publish(): the name is not empty,
/// and what is at `path` may be replaced only with force and only if it is a
/// regular file or a symbolic link to one. A directory, device, FIFO or
/// socket (or a link to one, or a dangling link) is refused even with force,
/// as SQLite refuses to open a non-regular database file. Throws
/// OutputFileError naming --out and the path.
void check_output_target(const std::string& path, bool force);

/// Renames `from` to `to`; without force never replaces an existing `to`;
/// with force, only a regular file (check_output_target).
/// `contents` names what `from` holds in the refusal: "the trajectory is".
void publish(const std::string& from, const std::string& to, bool force, const std::string& contents);

}  // namespace lgi::experiments::hdf5

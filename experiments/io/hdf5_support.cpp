#include "experiments/io/hdf5_support.hpp"

#include <fcntl.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>

#include "experiments/io/h5md_writer.hpp"  // OutputFileError, hdf5_library_version
#include "experiments/io/input_file.hpp"
#include "experiments/io/libm_code_path.hpp"
#include "lgi/build_info.hpp"

namespace lgi::experiments::hdf5 {

QuietHdf5Errors::QuietHdf5Errors() {
  H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

QuietHdf5Errors::~QuietHdf5Errors() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }

std::string hdf5_error_detail() {
  std::string out;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned n, const H5E_error2_t* e, void* data) -> herr_t {
        if (n == 0 && e != nullptr && e->desc != nullptr) *static_cast<std::string*>(data) = e->desc;
        return 0;
      },
      &out);
  for (char& c : out)
    if (c == '\n' || c == '\r') c = ' ';
  return out;
}

std::string errno_text(int err) { return std::strerror(err); }

std::string utc_now_iso8601() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string author_name() {
  for (const char* var : {"USER", "LOGNAME"}) {
    const char* v = std::getenv(var);
    if (v != nullptr && *v != '\0') return v;
  }
  return "unknown";
}

std::string parent_directory(const std::string& path) {
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

// ---- attributes -------------------------------------------------------------------

Handle scalar_space(const Fail& fail) {
  Handle s(H5Screate(H5S_SCALAR), H5Sclose);
  if (!s.valid()) fail("cannot create a dataspace");
  return s;
}

Handle vlen_string_type(bool ascii, const Fail& fail) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  if (!type.valid() || H5Tset_size(type.get(), H5T_VARIABLE) < 0 ||
      H5Tset_cset(type.get(), ascii ? H5T_CSET_ASCII : H5T_CSET_UTF8) < 0)
    fail("cannot make a string type");
  return type;
}

void write_attribute(hid_t obj, const char* name, hid_t file_type, hid_t memory_type, hid_t space, const void* data,
                     const Fail& fail) {
  const htri_t exists = H5Aexists(obj, name);
  if (exists < 0) fail(std::string("cannot query attribute ") + name);
  if (exists > 0 && H5Adelete(obj, name) < 0) fail(std::string("cannot replace attribute ") + name);
  Handle a(H5Acreate2(obj, name, file_type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!a.valid() || H5Awrite(a.get(), memory_type, data) < 0) fail(std::string("cannot write attribute ") + name);
}

void write_vlen_string(hid_t obj, const char* name, const std::string& value, bool ascii, const Fail& fail) {
  Handle type = vlen_string_type(ascii, fail);
  Handle space = scalar_space(fail);
  const char* p = value.c_str();
  write_attribute(obj, name, type.get(), type.get(), space.get(), &p, fail);
}

void write_fixed_string(hid_t obj, const char* name, const std::string& value, const Fail& fail) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  if (!type.valid() || H5Tset_size(type.get(), std::max<std::size_t>(1, value.size())) < 0 ||
      H5Tset_strpad(type.get(), H5T_STR_NULLPAD) < 0 || H5Tset_cset(type.get(), H5T_CSET_UTF8) < 0)
    fail("cannot make a string type");
  Handle space = scalar_space(fail);
  const std::string padded = value.empty() ? std::string(1, '\0') : value;
  write_attribute(obj, name, type.get(), type.get(), space.get(), padded.data(), fail);
}

void write_fixed_strings(hid_t obj, const char* name, const std::vector<std::string>& values, bool scalar,
                         const Fail& fail) {
  std::size_t width = 1;
  for (const auto& v : values) width = std::max(width, v.size() + 1);
  std::vector<char> buf(width * values.size(), '\0');
  for (std::size_t i = 0; i < values.size(); ++i) std::memcpy(&buf[i * width], values[i].data(), values[i].size());
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  if (!type.valid() || H5Tset_size(type.get(), width) < 0 || H5Tset_strpad(type.get(), H5T_STR_NULLTERM) < 0 ||
      H5Tset_cset(type.get(), H5T_CSET_UTF8) < 0)
    fail("cannot make a string type");
  const hsize_t n = values.size();
  Handle space(scalar ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &n, nullptr), H5Sclose);
  if (!space.valid()) fail("cannot create a dataspace");
  write_attribute(obj, name, type.get(), type.get(), space.get(), buf.data(), fail);
}

void write_int_attribute(hid_t obj, const char* name, hid_t file_type, std::int64_t value, const Fail& fail) {
  Handle space = scalar_space(fail);
  write_attribute(obj, name, file_type, H5T_NATIVE_INT64, space.get(), &value, fail);
}

void write_double_attribute(hid_t obj, const char* name, double value, const Fail& fail) {
  Handle space = scalar_space(fail);
  write_attribute(obj, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, space.get(), &value, fail);
}

void write_double_array(hid_t obj, const char* name, const std::vector<double>& values, const Fail& fail) {
  const hsize_t n = values.size();
  Handle space(n ? H5Screate_simple(1, &n, nullptr) : H5Screate(H5S_NULL), H5Sclose);
  if (!space.valid()) fail("cannot create a dataspace");
  write_attribute(obj, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, space.get(), values.data(), fail);
}

namespace {

/// 1-D H5T_STD_I32LE attribute (the H5MD version pairs).
void write_int32_array(hid_t obj, const char* name, const std::vector<std::int32_t>& values, const Fail& fail) {
  const hsize_t n = values.size();
  Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
  if (!space.valid()) fail("cannot create a dataspace");
  write_attribute(obj, name, H5T_STD_I32LE, H5T_NATIVE_INT32, space.get(), values.data(), fail);
}

}  // namespace

// ---- groups and files ------------------------------------------------------------------

namespace {
std::optional<std::string> read_string(hid_t obj, const char* name, bool allow_variable);
}

std::optional<std::string> read_string_attribute(hid_t obj, const char* name) { return read_string(obj, name, true); }
std::optional<std::string> read_fixed_string_attribute(hid_t obj, const char* name) {
  return read_string(obj, name, false);
}

namespace {
std::optional<std::string> read_string(hid_t obj, const char* name, bool allow_variable) {
  if (H5Aexists(obj, name) <= 0) return std::nullopt;
  Handle a(H5Aopen(obj, name, H5P_DEFAULT), H5Aclose);
  Handle type(a.valid() ? H5Aget_type(a.get()) : H5I_INVALID_HID, H5Tclose);
  Handle space(a.valid() ? H5Aget_space(a.get()) : H5I_INVALID_HID, H5Sclose);
  if (!type.valid() || !space.valid() || H5Tget_class(type.get()) != H5T_STRING ||
      H5Sget_simple_extent_type(space.get()) != H5S_SCALAR)
    return std::nullopt;
  const htri_t variable = H5Tis_variable_str(type.get());
  if (variable < 0 || (variable > 0 && !allow_variable)) return std::nullopt;
  Handle memory(H5Tcopy(H5T_C_S1), H5Tclose);
  const H5T_cset_t cset = H5Tget_cset(type.get());  // HDF5 converts no character set into another
  if (!memory.valid() || cset < 0 || H5Tset_cset(memory.get(), cset) < 0) return std::nullopt;
  if (variable > 0) {
    char* text = nullptr;
    if (H5Tset_size(memory.get(), H5T_VARIABLE) < 0 || H5Aread(a.get(), memory.get(), &text) < 0) return std::nullopt;
    std::optional<std::string> out;
    if (text != nullptr) out = std::string(text);
    H5free_memory(text);
    return out;
  }
  const std::size_t size = H5Tget_size(type.get());
  if (size == 0 || size > (std::size_t{1} << 26)) return std::nullopt;  // 64 MB: no attribute of lgi's is near
  std::string text(size + 1, '\0');
  if (H5Tset_size(memory.get(), size + 1) < 0 || H5Tset_strpad(memory.get(), H5T_STR_NULLTERM) < 0 ||
      H5Aread(a.get(), memory.get(), text.data()) < 0)
    return std::nullopt;
  text.resize(std::strlen(text.c_str()));
  return text;
}
}  // namespace

namespace {
std::optional<std::string> read_string_at(const std::string& path, const std::string& object, const char* name,
                                          bool* readable, bool allow_variable) {
  const QuietHdf5Errors quiet;
  if (readable) *readable = false;
  if (!hdf5_input_problem(path).empty() || H5Fis_hdf5(path.c_str()) <= 0) return std::nullopt;
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.valid()) return std::nullopt;
  if (readable) *readable = true;
  if (H5Lexists(file.get(), object.c_str(), H5P_DEFAULT) <= 0) return std::nullopt;
  Handle o(H5Oopen(file.get(), object.c_str(), H5P_DEFAULT), H5Oclose);
  if (!o.valid()) return std::nullopt;
  return read_string(o.get(), name, allow_variable);
}
}  // namespace

std::optional<std::string> read_string_attribute(const std::string& path, const std::string& object,
                                                 const char* name, bool* readable) {
  return read_string_at(path, object, name, readable, true);
}
std::optional<std::string> read_fixed_string_attribute(const std::string& path, const std::string& object,
                                                       const char* name, bool* readable) {
  return read_string_at(path, object, name, readable, false);
}

Handle create_group(hid_t loc, const std::string& path, const Fail& fail) {
  Handle g(H5Gcreate2(loc, path.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (!g.valid()) fail("cannot create group " + path);
  return g;
}

Handle open_or_create_group(hid_t parent, const std::string& name, const Fail& fail) {
  const htri_t exists = H5Lexists(parent, name.c_str(), H5P_DEFAULT);
  if (exists < 0) fail("cannot query group /" + name);
  Handle g(exists > 0 ? H5Gopen2(parent, name.c_str(), H5P_DEFAULT)
                      : H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
           H5Gclose);
  if (!g.valid()) fail("cannot create group " + name);
  return g;
}

Handle create_file(const std::string& path, const Fail& fail, std::size_t sieve_bytes) {
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  // STRONG: H5Fclose closes every object, so the file is complete when it returns.
  if (!fapl.valid() || H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG) < 0 ||
      H5Pset_sieve_buf_size(fapl.get(), sieve_bytes) < 0)
    fail("cannot set up file access");
  // Default library-version bounds (earliest format): no superblock status
  // flags, so a file left by a killed run opens without h5clear.
  Handle file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose);
  if (!file.valid()) fail("cannot create the HDF5 file");
  return file;
}

void write_h5md_metadata(hid_t file, bool units_module, const Fail& fail) {
  Handle h5md = create_group(file, "/h5md", fail);
  write_int32_array(h5md.get(), "version", {1, 1}, fail);
  Handle author = create_group(file, "/h5md/author", fail);
  write_fixed_strings(author.get(), "name", {author_name()}, true, fail);
  Handle creator = create_group(file, "/h5md/creator", fail);
  write_fixed_strings(creator.get(), "name", {"lgi"}, true, fail);
  write_fixed_strings(creator.get(), "version", {lgi::build_info::version}, true, fail);
  if (!units_module) return;
  // The H5MD units module (modules/units.mdwn) governs the `unit` attributes.
  Handle modules = create_group(file, "/h5md/modules", fail);
  Handle units = create_group(file, "/h5md/modules/units", fail);
  write_int32_array(units.get(), "version", {1, 0}, fail);
  write_vlen_string(units.get(), "system", "SI", /*ascii=*/true, fail);
}

std::vector<std::pair<std::string, std::string>> default_provenance(const std::string& utc_start) {
  return {{"compiler", lgi::build_info::compiler},
          {"cxx_flags", lgi::build_info::cxx_flags},
          {"build_type", lgi::build_info::build_type},
          {"libm", libm_code_path()},
          {"hdf5_version", hdf5_library_version()},
          {"utc_start", utc_start}};
}

// ---- CSV and publishing ---------------------------------------------------------------

std::string csv_number(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);  // shortest round-trip form
  return std::string(buf, r.ptr);
}

std::string csv_text(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + '"';
}

bool path_exists(const std::string& path) {
  struct stat st {};
  return ::lstat(path.c_str(), &st) == 0;
}

namespace {
const char* file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}
}  // namespace

void check_output_target(const std::string& path, bool force) {
  if (path.empty()) throw OutputFileError("--out: an empty file name");
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return;  // nothing there (or the directory is refused on creation)
  const bool link = S_ISLNK(st.st_mode);
  if (link && ::stat(path.c_str(), &st) != 0)
    throw OutputFileError("--out: '" + path + "' is a symbolic link to nothing; lgi replaces only a regular file");
  if (!S_ISREG(st.st_mode))
    throw OutputFileError("--out: '" + path + "' is " + (link ? "a link to " : "") + file_kind(st.st_mode) +
                          "; lgi replaces only a regular file, even with --force");
  if (!force) throw OutputFileError("--out: '" + path + "' exists (use --force to replace it)");
}

void publish(const std::string& from, const std::string& to, bool force, const std::string& contents) {
  const std::string appeared = "output file '" + to + "' appeared during the run; " + contents + " in '" + from + "'";
  if (!force) {
    if (::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE) == 0) return;
    const int err = errno;
    if (err == EEXIST) throw OutputFileError(appeared);
    if (err != EINVAL && err != ENOSYS && err != ENOTSUP)
      throw OutputFileError("cannot rename '" + from + "' to '" + to + "': " + errno_text(err));
    if (path_exists(to)) throw OutputFileError(appeared);  // file system without RENAME_NOREPLACE
  }
  check_output_target(to, true);  // what appeared at `to` meanwhile is no more replaceable than before
  if (std::rename(from.c_str(), to.c_str()) != 0)
    throw OutputFileError("cannot rename '" + from + "' to '" + to + "': " + errno_text(errno));
}

}  // namespace lgi::experiments::hdf5

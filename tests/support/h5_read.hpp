#pragma once
// Minimal HDF5 reading for tests (C API): a dataset as a flat vector of
// doubles with its shape, and string attributes.
#include <hdf5.h>

#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace lgi::testing {

struct H5Array {
  std::vector<double> data;
  std::vector<hsize_t> shape;
};

/// The file (read-only) and one of its datasets; throws naming what is missing.
/// The caller closes both.
inline std::pair<hid_t, hid_t> open_dataset(const std::string& file, const std::string& name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) throw std::runtime_error("cannot open " + file);
  const hid_t d = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
  if (d < 0) {
    H5Fclose(f);
    throw std::runtime_error("no dataset " + name + " in " + file);
  }
  return {f, d};
}

inline H5Array read_dataset(const std::string& file, const std::string& name) {
  const auto [f, d] = open_dataset(file, name);
  const hid_t sp = H5Dget_space(d);
  const int rank = H5Sget_simple_extent_ndims(sp);
  H5Array a;
  a.shape.resize(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(sp, a.shape.data(), nullptr);
  hsize_t n = 1;
  for (auto s : a.shape) n *= s;
  a.data.resize(n);
  if (n) H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, a.data.data());
  H5Sclose(sp);
  H5Dclose(d);
  H5Fclose(f);
  return a;
}

inline std::string read_string_attribute(const std::string& file, const std::string& object, const std::string& attr) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) throw std::runtime_error("cannot open " + file);
  const hid_t a = H5Aopen_by_name(f, object.c_str(), attr.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  std::string out;
  if (a >= 0) {
    const hid_t t = H5Aget_type(a);
    if (H5Tis_variable_str(t) > 0) {
      char* s = nullptr;
      const hid_t mt = H5Tcopy(H5T_C_S1);
      H5Tset_size(mt, H5T_VARIABLE);
      H5Tset_cset(mt, H5Tget_cset(t));
      H5Aread(a, mt, &s);
      if (s) out = s;
      H5free_memory(s);
      H5Tclose(mt);
    } else {
      const std::size_t size = H5Tget_size(t);
      std::vector<char> buf(size + 1, '\0');
      H5Aread(a, t, buf.data());
      out = std::string(buf.data());
    }
    H5Tclose(t);
    H5Aclose(a);
  }
  H5Fclose(f);
  return out;
}

/// A 1-D dataset of strings (variable- or fixed-length) as a vector.
inline std::vector<std::string> read_string_dataset(const std::string& file, const std::string& name) {
  const auto [f, d] = open_dataset(file, name);
  const hid_t sp = H5Dget_space(d);
  hsize_t n = 0;
  H5Sget_simple_extent_dims(sp, &n, nullptr);
  const hid_t t = H5Dget_type(d);
  std::vector<std::string> out;
  if (H5Tis_variable_str(t) > 0) {
    std::vector<char*> p(n, nullptr);
    const hid_t mt = H5Tcopy(H5T_C_S1);
    H5Tset_size(mt, H5T_VARIABLE);
    H5Tset_cset(mt, H5Tget_cset(t));
    if (n) H5Dread(d, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, p.data());
    for (char* c : p) out.emplace_back(c ? c : "");
    if (n) H5Dvlen_reclaim(mt, sp, H5P_DEFAULT, p.data());
    H5Tclose(mt);
  } else {
    const std::size_t size = H5Tget_size(t);
    std::vector<char> buf(size * n + 1, '\0');
    if (n) H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data());
    for (hsize_t i = 0; i < n; ++i) out.emplace_back(std::string(&buf[i * size], size).c_str());
  }
  H5Tclose(t);
  H5Sclose(sp);
  H5Dclose(d);
  H5Fclose(f);
  return out;
}

/// A scalar numeric attribute as a double (NaN if absent).
inline double read_double_attribute(const std::string& file, const std::string& object, const std::string& attr) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) throw std::runtime_error("cannot open " + file);
  double v = std::numeric_limits<double>::quiet_NaN();
  const hid_t a = H5Aopen_by_name(f, object.c_str(), attr.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  if (a >= 0) {
    H5Aread(a, H5T_NATIVE_DOUBLE, &v);
    H5Aclose(a);
  }
  H5Fclose(f);
  return v;
}

/// A scalar integer attribute (-999 if absent).
inline std::int64_t read_integer_attribute(const std::string& file, const std::string& object,
                                           const std::string& attr) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) throw std::runtime_error("cannot open " + file);
  std::int64_t v = -999;
  const hid_t a = H5Aopen_by_name(f, object.c_str(), attr.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  if (a >= 0) {
    H5Aread(a, H5T_NATIVE_INT64, &v);
    H5Aclose(a);
  }
  H5Fclose(f);
  return v;
}

}  // namespace lgi::testing

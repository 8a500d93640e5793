// Result files read back into NumPy (hdf5_columns.hpp), with the HDF5 C API.
#include "python/src/hdf5_columns.hpp"

#include <pybind11/stl.h>
#include <stdlib.h>

#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "experiments/io/hdf5_support.hpp"

namespace lgi::python {
namespace {

namespace fs = std::filesystem;
using experiments::hdf5::Handle;

herr_t collect_name(hid_t, const char* name, const H5L_info_t*, void* names) {
  static_cast<std::vector<std::string>*>(names)->push_back(name);
  return 0;
}

herr_t collect_attribute(hid_t, const char* name, const H5A_info_t*, void* names) {
  static_cast<std::vector<std::string>*>(names)->push_back(name);
  return 0;
}

Column read_column(hid_t group, const std::string& name, const std::string& where) {
  Column c;
  c.name = name;
  const Handle set(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose);
  const Handle type(H5Dget_type(set.get()), H5Tclose), space(H5Dget_space(set.get()), H5Sclose);
  c.type_class = H5Tget_class(type.get());
  c.dims.resize(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space.get())));
  H5Sget_simple_extent_dims(space.get(), c.dims.data(), nullptr);
  std::size_t count = 1;
  for (hsize_t d : c.dims) count *= static_cast<std::size_t>(d);
  Handle memory(H5Tcopy(c.type_class == H5T_INTEGER ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE), H5Tclose);
  std::size_t width = 8;
  if (c.type_class == H5T_STRING) {
    memory = Handle(H5Tcopy(type.get()), H5Tclose);
    width = c.text_size = H5Tget_size(type.get());
  }
  c.bytes.resize(count * width);
  const herr_t status = count ? H5Dread(set.get(), memory.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, c.bytes.data()) : 0;
  if (status < 0) throw std::runtime_error(where + ": cannot read " + name);
  return c;
}

Handle open_file(const std::string& path) {
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.valid()) throw std::runtime_error("cannot open " + path);
  return file;
}

}  // namespace

std::vector<Column> read_group_columns(const std::string& path, const std::string& group) {
  const Handle file = open_file(path);
  const Handle g(H5Gopen2(file.get(), group.c_str(), H5P_DEFAULT), H5Gclose);
  if (!g.valid()) throw std::runtime_error(path + ": no group " + group);
  std::vector<std::string> names;
  H5Literate(g.get(), H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_name, &names);
  std::vector<Column> columns;
  for (const auto& name : names) columns.push_back(read_column(g.get(), name, path + ":" + group));
  return columns;
}

py::array column_array(const Column& c) {
  py::module_ np = py::module_::import("numpy");
  std::vector<py::ssize_t> shape;
  for (hsize_t d : c.dims) shape.push_back(static_cast<py::ssize_t>(d));
  const std::string format = c.type_class == H5T_INTEGER  ? "<i8"
                             : c.type_class == H5T_STRING ? "S" + std::to_string(c.text_size)
                                                          : "<f8";
  py::array a = np.attr("frombuffer")(py::bytes(c.bytes.data(), c.bytes.size()), format).attr("reshape")(shape);
  if (c.type_class == H5T_STRING) a = np.attr("char").attr("decode")(a, "utf-8");
  return np.attr("array")(a);  // a writable copy that owns its memory
}

py::dict group_dict(const std::string& path, const std::string& group) {
  py::dict d;
  for (const Column& c : read_group_columns(path, group)) d[py::str(c.name)] = column_array(c);
  return d;
}

py::dict attributes_dict(const std::string& path, const std::string& object) {
  const Handle file = open_file(path);
  const Handle o(H5Oopen(file.get(), object.c_str(), H5P_DEFAULT), H5Oclose);
  if (!o.valid()) throw std::runtime_error(path + ": no object " + object);
  std::vector<std::string> names;
  H5Aiterate2(o.get(), H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_attribute, &names);
  py::dict d;
  for (const auto& name : names) {
    const Handle a(H5Aopen(o.get(), name.c_str(), H5P_DEFAULT), H5Aclose);
    const Handle type(H5Aget_type(a.get()), H5Tclose), space(H5Aget_space(a.get()), H5Sclose);
    if (H5Sget_simple_extent_type(space.get()) != H5S_SCALAR) continue;
    const H5T_class_t k = H5Tget_class(type.get());
    if (k == H5T_STRING) {
      if (const auto text = experiments::hdf5::read_string_attribute(o.get(), name.c_str())) d[py::str(name)] = *text;
    } else if (k == H5T_INTEGER) {
      std::int64_t v = 0;
      if (H5Aread(a.get(), H5T_NATIVE_INT64, &v) >= 0) d[py::str(name)] = v;
    } else if (k == H5T_FLOAT) {
      double v = 0.0;
      if (H5Aread(a.get(), H5T_NATIVE_DOUBLE, &v) >= 0) d[py::str(name)] = v;
    }
  }
  return d;
}

TemporaryFolder::TemporaryFolder(const std::string& prefix) {
  std::string pattern = (fs::temp_directory_path() / (prefix + "-XXXXXX")).string();
  if (!mkdtemp(pattern.data())) throw std::runtime_error(prefix + ": cannot create a temporary folder");
  path = pattern;
}

TemporaryFolder::~TemporaryFolder() {
  std::error_code ec;
  fs::remove_all(path, ec);
}

}  // namespace lgi::python

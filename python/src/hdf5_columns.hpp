#pragma once
// Result files read back into NumPy for the bindings that run a command's
// engine into a file (lgi.sweep, lgi.poincare): every dataset of a group as
// an array (int64, float64 or text; n or n x k), and an object's scalar
// attributes. Errors raise RuntimeError naming the file and the group.
#include <hdf5.h>

#include <string>
#include <vector>

#include "python/src/bindings.hpp"

namespace lgi::python {

/// One dataset of a group: int64, float64 or fixed-length text; n or n x k.
struct Column {
  std::string name;
  H5T_class_t type_class = H5T_NO_CLASS;
  std::size_t text_size = 0;
  std::vector<hsize_t> dims;
  std::vector<char> bytes;
};

/// Every dataset of `group` (e.g. "/sweep") in the file, by name.
std::vector<Column> read_group_columns(const std::string& path, const std::string& group);

/// A column as a NumPy array (text decoded as UTF-8 str).
py::array column_array(const Column& c);

/// {name: array} of every dataset of `group`.
py::dict group_dict(const std::string& path, const std::string& group);

/// {name: value} of the scalar attributes of `object` (text as str, numbers as float or int).
py::dict attributes_dict(const std::string& path, const std::string& object);

/// A fresh private folder under the system's temporary folder, removed with its contents.
struct TemporaryFolder {
  std::string path;
  explicit TemporaryFolder(const std::string& prefix);
  ~TemporaryFolder();
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
};

}  // namespace lgi::python

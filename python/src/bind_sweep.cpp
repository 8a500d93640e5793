// lgi.sweep(): `lgi sweep` run in-process (experiments/cli/commands.hpp,
// run_sweep_request: the same spec checks, engine, threads and file), its
// /sweep table read back with the HDF5 C API into a NumPy structured array.
#include <hdf5.h>
#include <pybind11/stl.h>
#include <stdlib.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "experiments/cli/commands.hpp"
#include "python/src/bindings.hpp"

namespace lgi::python {
namespace {

namespace fs = std::filesystem;

/// One /sweep column: int64, float64 or fixed-length text; n or n x k.
struct Column {
  std::string name;
  H5T_class_t type_class = H5T_NO_CLASS;
  std::size_t text_size = 0;
  std::vector<hsize_t> dims;
  std::vector<char> bytes;
};

herr_t collect_name(hid_t, const char* name, const H5L_info_t*, void* names) {
  static_cast<std::vector<std::string>*>(names)->push_back(name);
  return 0;
}

Column read_column(hid_t group, const std::string& name) {
  Column c;
  c.name = name;
  const hid_t set = H5Dopen2(group, name.c_str(), H5P_DEFAULT);
  const hid_t type = H5Dget_type(set), space = H5Dget_space(set);
  c.type_class = H5Tget_class(type);
  c.dims.resize(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, c.dims.data(), nullptr);
  std::size_t count = 1;
  for (hsize_t d : c.dims) count *= static_cast<std::size_t>(d);
  hid_t memory = c.type_class == H5T_INTEGER ? H5Tcopy(H5T_NATIVE_INT64) : H5Tcopy(H5T_NATIVE_DOUBLE);
  std::size_t width = 8;
  if (c.type_class == H5T_STRING) {
    H5Tclose(memory);
    memory = H5Tcopy(type);
    width = c.text_size = H5Tget_size(type);
  }
  c.bytes.resize(count * width);
  const herr_t status = count ? H5Dread(set, memory, H5S_ALL, H5S_ALL, H5P_DEFAULT, c.bytes.data()) : 0;
  H5Tclose(memory);
  H5Sclose(space);
  H5Tclose(type);
  H5Dclose(set);
  if (status < 0) throw std::runtime_error("lgi.sweep: cannot read /sweep/" + name);
  return c;
}

std::vector<Column> read_sweep_table(const std::string& path) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) throw std::runtime_error("lgi.sweep: cannot open " + path);
  const hid_t group = H5Gopen2(file, "/sweep", H5P_DEFAULT);
  std::vector<std::string> names;
  H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_name, &names);
  std::vector<Column> columns;
  for (const auto& name : names) columns.push_back(read_column(group, name));
  H5Gclose(group);
  H5Fclose(file);
  return columns;
}

/// The columns as one structured array, `index` first, the others by name.
py::array structured_array(std::vector<Column>& columns) {
  py::module_ np = py::module_::import("numpy");
  std::stable_partition(columns.begin(), columns.end(), [](const Column& c) { return c.name == "index"; });
  const auto rows = columns.empty() || columns[0].dims.empty() ? py::ssize_t{0} : static_cast<py::ssize_t>(columns[0].dims[0]);
  py::list descr;
  std::vector<py::array> arrays;
  for (Column& c : columns) {
    std::vector<py::ssize_t> shape;
    for (hsize_t d : c.dims) shape.push_back(static_cast<py::ssize_t>(d));
    const std::string format = c.type_class == H5T_INTEGER ? "<i8" : c.type_class == H5T_STRING ? "S" + std::to_string(c.text_size) : "<f8";
    py::array a = np.attr("frombuffer")(py::bytes(c.bytes.data(), c.bytes.size()), format).attr("reshape")(shape);
    if (c.type_class == H5T_STRING) a = np.attr("char").attr("decode")(a, "utf-8");
    py::tuple sub = shape.size() > 1 ? py::make_tuple(shape[1]) : py::make_tuple();
    descr.append(py::make_tuple(c.name, a.attr("dtype").attr("str"), sub));
    arrays.push_back(a);
  }
  py::array table = np.attr("zeros")(rows, np.attr("dtype")(descr));
  for (std::size_t k = 0; k < columns.size(); ++k) table[py::str(columns[k].name)] = arrays[k];
  return table;
}

/// A fresh private folder for the spec of a dict and the file of a call without out=.
struct TemporaryFolder {
  fs::path path;
  TemporaryFolder() {
    std::string pattern = (fs::temp_directory_path() / "lgi-sweep-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("lgi.sweep: cannot create a temporary folder");
    path = pattern;
  }
  ~TemporaryFolder() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
};

/// The spec file: a path as given; a dict written as TOML (its relative scene path made absolute).
std::string spec_file(const py::object& spec, const TemporaryFolder& folder) {
  if (!py::isinstance<py::dict>(spec)) return py::str(spec).cast<std::string>();
  py::dict d = py::dict(spec);
  if (d.contains("scene") && py::isinstance<py::str>(d["scene"]))
    d["scene"] = fs::absolute(d["scene"].cast<std::string>()).string();
  const fs::path path = folder.path / "spec.toml";
  std::ofstream(path) << toml_text_from_dict(d);
  return path.string();
}

py::array sweep(const py::object& spec, int threads, const std::optional<std::string>& out, bool force) {
  if (threads < 1) throw py::value_error("threads: must be >= 1");
  const TemporaryFolder folder;
  experiments::SweepRequest request;
  request.spec = spec_file(spec, folder);
  request.out = out ? *out : (folder.path / "sweep.h5").string();
  request.threads = threads;
  request.force = force;
  request.command_line = "lgi.sweep(spec='" + request.spec + "')";
  int status = 0;
  {
    const py::gil_scoped_release release;
    status = experiments::run_sweep_request(request);
  }
  if (status != 0) throw std::runtime_error("lgi.sweep: the sweep did not complete (exit status " + std::to_string(status) + ")");
  std::vector<Column> columns = read_sweep_table(request.out);
  return structured_array(columns);
}

}  // namespace

void bind_sweep(py::module_& m) {
  m.def("sweep", &sweep, py::arg("spec"), py::arg("threads") = 1, py::arg("out") = py::none(),
        py::arg("force") = false,
        "sweep(spec, threads=1, out=None, force=False) -> numpy structured array: `lgi sweep` in-process.\n"
        "`spec` is a sweep spec file (experiments/SWEEPS.md) or a dict with its keys (a relative `scene`\n"
        "is taken from the current folder). Returns the /sweep table, one row per trajectory: index,\n"
        "the varied inputs, status, reason, steps, cpu_seconds, t_final, the final state\n"
        "(angular_momentum, orientation, gamma), max_<invariant>_error, event and sample counts.\n"
        "With out= the whole result file (events, trajectories) is kept there, as the CLI writes it;\n"
        "otherwise nothing is left on disk. Runs on `threads` OpenMP threads with the GIL released.\n"
        "ValueError for a bad spec (the CLI's message).");
}

}  // namespace lgi::python

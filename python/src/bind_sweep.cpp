// lgi.sweep(): `lgi sweep` run in-process (experiments/commands/sweep_request.hpp,
// run_sweep_request: the same spec checks, engine, threads and file), its
// /sweep table read back with the HDF5 C API into a NumPy structured array.
#include <pybind11/stl.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "experiments/commands/sweep_request.hpp"
#include "experiments/cli/thread_count.hpp"
#include "python/src/bindings.hpp"
#include "python/src/hdf5_columns.hpp"

namespace lgi::python {
namespace {

namespace fs = std::filesystem;

/// The columns as one structured array, `index` first, the others by name.
py::array structured_array(std::vector<Column>& columns) {
  py::module_ np = py::module_::import("numpy");
  std::stable_partition(columns.begin(), columns.end(), [](const Column& c) { return c.name == "index"; });
  const auto rows = columns.empty() || columns[0].dims.empty() ? py::ssize_t{0} : static_cast<py::ssize_t>(columns[0].dims[0]);
  py::list descr;
  std::vector<py::array> arrays;
  for (const Column& c : columns) {
    py::array a = column_array(c);
    py::tuple sub = c.dims.size() > 1 ? py::make_tuple(static_cast<py::ssize_t>(c.dims[1])) : py::make_tuple();
    descr.append(py::make_tuple(c.name, a.attr("dtype").attr("str"), sub));
    arrays.push_back(a);
  }
  py::array table = np.attr("zeros")(rows, np.attr("dtype")(descr));
  for (std::size_t k = 0; k < columns.size(); ++k) table[py::str(columns[k].name)] = arrays[k];
  return table;
}

/// The spec file: a path as given; a dict written as TOML (its relative scene path made absolute).
std::string spec_file(const py::object& spec, const TemporaryFolder& folder) {
  if (!py::isinstance<py::dict>(spec)) return py::str(spec).cast<std::string>();
  py::dict d = py::dict(spec);
  if (d.contains("scene") && py::isinstance<py::str>(d["scene"]))
    d["scene"] = fs::absolute(d["scene"].cast<std::string>()).string();
  const fs::path path = fs::path(folder.path) / "spec.toml";
  std::ofstream(path) << toml_text_from_dict(d);
  return path.string();
}

py::array sweep(const py::object& spec, int threads, const std::optional<std::string>& out, bool force) {
  if (threads < 1 || threads > experiments::max_threads())
    throw py::value_error("threads: must be from 1 to " + std::to_string(experiments::max_threads()) + " (64 per core)");
  const TemporaryFolder folder("lgi-sweep");
  experiments::SweepRequest request;
  request.spec = spec_file(spec, folder);
  request.out = out ? *out : (fs::path(folder.path) / "sweep.h5").string();
  request.threads = threads;
  request.force = force;
  request.command_line = "lgi.sweep(spec='" + request.spec + "')";
  int status = 0;
  {
    const py::gil_scoped_release release;
    status = experiments::run_sweep_request(request);
  }
  if (status != 0) throw std::runtime_error("lgi.sweep: the sweep did not complete (exit status " + std::to_string(status) + ")");
  std::vector<Column> columns = read_group_columns(request.out, "/sweep");
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

// lgi.schemes(), lgi.scenes() and lgi.scenes_dir(): the registry and the
// shipped scenes with their metadata, from the code behind `lgi schemes
// --json` (experiments/cli/scheme_record.hpp) and `lgi scenes`
// (experiments/io/scenes_location.hpp).
#include <pybind11/stl.h>

#include <optional>
#include <string>

#include "experiments/cli/scheme_lookup.hpp"
#include "experiments/cli/scheme_record.hpp"
#include "experiments/errors/input_error.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/scenes_location.hpp"
#include "integrators/system/invariants.hpp"
#include "python/src/bindings.hpp"

#ifndef LGI_PYTHON_SCENES_INSTALLED
#define LGI_PYTHON_SCENES_INSTALLED "../../../../share/lgi/scenes"
#endif

namespace lgi::python {
namespace {

py::object field_value(const experiments::SchemeField& f) {
  struct ToPython {
    py::object operator()(std::monostate) const { return py::none(); }
    py::object operator()(bool b) const { return py::bool_(b); }
    py::object operator()(int i) const { return py::int_(i); }
    py::object operator()(const std::string& s) const { return py::str(s); }
  };
  return std::visit(ToPython{}, f.value);
}

/// The record of `lgi schemes --json`, with the properties grouped in a
/// dict and "scenes" named "support".
py::dict scheme_dict(const integrators::SchemeInfo& s) {
  py::dict d, properties;
  for (const experiments::SchemeField& f : experiments::scheme_record(s, std::nullopt)) {
    if (f.property) properties[py::str(f.key)] = field_value(f);
    else d[py::str(f.key == "scenes" ? std::string("support") : f.key)] = field_value(f);
  }
  d["properties"] = properties;
  return d;
}

py::list schemes() {
  py::list out;
  for (const integrators::SchemeInfo* s : experiments::listed_schemes()) out.append(scheme_dict(*s));
  return out;
}

std::string scenes_dir(const std::optional<std::string>& directory) {
  return experiments::shipped_scenes_dir(directory.value_or(""), extension_path(),
                                         {LGI_PYTHON_SCENES_INSTALLED, "../../../../experiments/scenes"});
}

py::dict scene_dict(const std::filesystem::path& file) {
  const system::Scene scene = experiments::read_scene(file.string());
  const system::AnyModel model = system::make_model(scene);
  const system::SceneInvariants invariants(scene, model);
  py::dict d;
  d["file"] = file.filename().string();
  d["path"] = file.string();
  d["name"] = scene.name;
  d["description"] = scene.description;
  d["invariants"] = invariants.all_names();
  d["free_body"] = scene.is_free_body();
  d["t_end"] = optional_number(scene.t_end);
  d["dt"] = optional_number(scene.dt);
  d["tol"] = optional_number(scene.tol);
  return d;
}

py::list scenes(const std::optional<std::string>& directory) {
  const std::string folder = scenes_dir(directory);
  py::list out;
  for (const auto& file : experiments::scene_files(folder)) {
    try {
      out.append(scene_dict(file));
    } catch (const experiments::InputError& e) {  // as `lgi scenes`: say why, list the others
      PyErr_WarnEx(PyExc_UserWarning, e.what(), 1);
    }
  }
  return out;
}

}  // namespace

void bind_catalog(py::module_& m) {
  m.def("schemes", &schemes,
        "Every registered scheme, as `lgi schemes --json` lists them: a list of dicts with name, order,\n"
        "order_with_torque, family, kind ('lie-group', 'composition', 'baseline', 'exact'), base (a\n"
        "composition's base scheme or None), properties (dict of bools: symplectic, symmetric,\n"
        "conserves_energy, conserves_momentum_norm, conserves_spatial_momentum,\n"
        "conserves_vertical_momentum, baseline, implicit, adaptive), support ('all scenes',\n"
        "'conservative', 'free bodies'), reference and notes.");
  m.def("scenes_dir", &scenes_dir, py::arg("directory") = py::none(),
        "The folder of the shipped scenes: `directory` if given; else $LGI_SCENES_DIR; else the\n"
        "installed share/lgi/scenes beside the package, or the source tree's experiments/scenes for\n"
        "the build tree's module. ValueError if none is found.");
  m.def("scenes", &scenes, py::arg("directory") = py::none(),
        "The scene files of a folder (default: scenes_dir()), as `lgi scenes` lists them: a list of\n"
        "dicts with file, path, name, description, invariants (names), free_body, and the [run]\n"
        "defaults t_end, dt, tol (None where absent). A file that does not read is skipped with a\n"
        "UserWarning carrying the reader's message.");
}

}  // namespace lgi::python

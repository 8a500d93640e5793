// lgi.Scene: a scene read by the command line's scene reader
// (experiments/io/scene_reader.hpp), from a file, from TOML text, or from
// keyword arguments with the keys of the scene file (turned into TOML text
// first, so every check and every message is the reader's).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <regex>
#include <sstream>
#include <toml++/toml.h>

#include "experiments/io/scene_reader.hpp"
#include "integrators/system/invariants.hpp"
#include "python/src/bindings.hpp"

namespace lgi::python {
namespace {

toml::table toml_table_from(const py::handle& dict);
toml::array toml_array_from(const py::handle& list);

/// Hands one keyword value to `sink` as its TOML type (a NumPy array or scalar
/// through tolist()): bool, integer, float, string, table (dict) or array
/// (list, tuple; lists of dicts are arrays of tables).
template <class Sink>
void emit_toml(const py::handle& v, const std::string& where, Sink&& sink) {
  if (py::hasattr(v, "tolist") && !py::isinstance<py::str>(v)) return emit_toml(v.attr("tolist")(), where, sink);
  if (py::isinstance<py::bool_>(v)) return sink(v.cast<bool>());
  if (py::isinstance<py::int_>(v)) return sink(v.cast<int64_t>());
  if (py::isinstance<py::float_>(v)) return sink(v.cast<double>());
  if (py::isinstance<py::str>(v)) return sink(v.cast<std::string>());
  if (py::isinstance<py::dict>(v)) return sink(toml_table_from(v));
  if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) return sink(toml_array_from(v));
  throw py::type_error("Scene: " + where + py::repr(v).cast<std::string>() + " has no TOML form");
}

toml::table toml_table_from(const py::handle& dict) {
  toml::table out;
  for (const auto& [key, item] : dict.cast<py::dict>()) {
    const std::string name = py::str(key).cast<std::string>();
    emit_toml(item, "key '" + name + "': ", [&](auto&& value) { out.insert_or_assign(name, std::move(value)); });
  }
  return out;
}

toml::array toml_array_from(const py::handle& list) {
  toml::array out;
  for (const py::handle item : list) emit_toml(item, "", [&](auto&& value) { out.push_back(std::move(value)); });
  return out;
}

/// "Scene(**kwargs):12: [body] inertia: ..." -> "Scene(**kwargs): [body] inertia: ...": the line
/// numbers of the generated text mean nothing to the caller.
std::string without_line_number(const std::string& message, const std::string& source) {
  const std::regex line("^" + std::regex_replace(source, std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") + R"(:\d+:)");
  return std::regex_replace(message, line, source + ":", std::regex_constants::format_first_only);
}

PyScene scene_from_kwargs(const py::kwargs& kwargs) {
  const std::string source = "Scene(**kwargs)";
  const std::string text = toml_text_from_dict(kwargs);
  try {
    return {std::make_shared<const system::Scene>(experiments::parse_scene(text, source))};
  } catch (const experiments::InputError& e) {
    throw py::value_error(without_line_number(e.what(), source));
  }
}

PyScene scene_from_file(const std::string& path) {
  return {std::make_shared<const system::Scene>(experiments::read_scene(path))};
}

PyScene scene_from_toml(const std::string& text, const std::string& name) {
  return {std::make_shared<const system::Scene>(experiments::parse_scene(text, name))};
}

std::vector<std::string> invariant_names(const system::Scene& scene) {
  const system::AnyModel model = system::make_model(scene);
  return system::SceneInvariants(scene, model).all_names();
}

/// A 3x3 matrix as a row-major NumPy array (docs/conventions.md: matrices are row-major).
py::array_t<double> matrix_array(const lie::Mat3& M) {
  std::vector<double> v(9);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) v[static_cast<std::size_t>(3 * r + c)] = M(r, c);
  return to_numpy(std::move(v), {3, 3});
}

py::array_t<double> vector_array(const lie::Vec3& x) { return to_numpy(std::vector<double>{x[0], x[1], x[2]}, {3}); }

void bind_scene_properties(py::class_<PyScene>& c) {
  c.def_property_readonly("name", [](const PyScene& s) { return s.scene->name; }, "The scene's name.")
      .def_property_readonly("description", [](const PyScene& s) { return s.scene->description; })
      .def_property_readonly("file", [](const PyScene& s) { return s.scene->file; },
                             "The file it was read from (or 'Scene(**kwargs)', or the name given to from_toml).")
      .def_property_readonly("toml", [](const PyScene& s) { return s.scene->toml_text; }, "The full TOML text.")
      .def_property_readonly("inertia", [](const PyScene& s) { return matrix_array(s.scene->inertia); },
                             "J about the reference point, kg m^2 (3x3).")
      .def_property_readonly("mass", [](const PyScene& s) { return optional_number(s.scene->mass); })
      .def_property_readonly("center_of_mass", [](const PyScene& s) -> py::object {
        if (!s.scene->center_of_mass) return py::none();
        return vector_array(*s.scene->center_of_mass);
      }, "chi in body coordinates from the fixed point, m (None if the scene has none).")
      .def_property_readonly("R0", [](const PyScene& s) { return matrix_array(s.scene->initial.R); },
                             "The initial attitude R (body -> space, 3x3).")
      .def_property_readonly("Pi0", [](const PyScene& s) { return vector_array(s.scene->initial.Pi); },
                             "The initial body angular momentum Pi, kg m^2/s.")
      .def_property_readonly("t_end", [](const PyScene& s) { return optional_number(s.scene->t_end); },
                             "[run] t_end, or None.")
      .def_property_readonly("dt", [](const PyScene& s) { return optional_number(s.scene->dt); }, "[run] dt, or None.")
      .def_property_readonly("tol", [](const PyScene& s) { return optional_number(s.scene->tol); }, "[run] tol, or None.")
      .def_property_readonly("free_body", [](const PyScene& s) { return s.scene->is_free_body(); },
                             "True if the scene declares no torque term.")
      .def_property_readonly("invariants", [](const PyScene& s) { return invariant_names(*s.scene); },
                             "The names of the invariants that apply (as `lgi scenes`).");
}

}  // namespace

std::string toml_text_from_dict(const py::dict& d) {
  std::ostringstream text;
  text << toml_table_from(d) << '\n';
  return text.str();
}

std::shared_ptr<const system::Scene> scene_argument(const py::object& obj) {
  if (py::isinstance<PyScene>(obj)) return obj.cast<const PyScene&>().scene;
  if (py::isinstance<py::str>(obj) || py::hasattr(obj, "__fspath__"))
    return scene_from_file(py::str(obj).cast<std::string>()).scene;
  throw py::type_error("scene: expected an lgi.Scene or the path of a scene file, got " +
                       py::repr(obj).cast<std::string>());
}

void bind_scene(py::module_& m) {
  py::class_<PyScene> c(m, "Scene",
                        "A scene: the body, its torques, the initial state and the [run] defaults.\n\n"
                        "Scene(**keys) takes the keys of a scene file (experiments/scenes/README.md), tables as\n"
                        "dicts and arrays of tables as lists of dicts, e.g.\n"
                        "    lgi.Scene(name='book', body={'inertia': [0.01203, 0.0074, 0.0048]},\n"
                        "              initial={'angular_velocity': [0.01, 10.0, 0.01]})\n"
                        "and checks them with the command line's reader: bad input raises ValueError whose\n"
                        "message names the key as lgi does ('Scene(**kwargs): [body] inertia: ...').\n"
                        "Scene.from_file(path) reads a scene file, Scene.from_toml(text) TOML text.");
  c.def(py::init(&scene_from_kwargs))
      .def_static("from_file", &scene_from_file, py::arg("path"),
                  "Reads a scene file; ValueError with lgi's message ('<file>:<line>: [table] key: ...').")
      .def_static("from_toml", &scene_from_toml, py::arg("text"), py::arg("name") = "<string>",
                  "Parses scene TOML text; `name` stands for the file in messages.")
      .def("__repr__", [](const PyScene& s) { return "lgi.Scene('" + s.scene->name + "', file='" + s.scene->file + "')"; });
  bind_scene_properties(c);
}

}  // namespace lgi::python

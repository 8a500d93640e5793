#pragma once
// The Python module lgi (python/README.md): one bind_<what>() per binding
// file, called from module.cpp, and the helpers they share.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "integrators/registry/registry.hpp"
#include "integrators/system/scene.hpp"

namespace lgi::python {

namespace py = pybind11;

void bind_catalog(py::module_& m);     // bind_catalog.cpp: schemes(), scenes()
void bind_scene(py::module_& m);       // bind_scene.cpp: Scene
void bind_simulate(py::module_& m);    // bind_simulate.cpp: simulate()
void bind_stepper(py::module_& m);     // bind_stepper.cpp: Stepper
void bind_exact_flow(py::module_& m);  // bind_exact_flow.cpp: exact_free_flow()
void bind_sweep(py::module_& m);       // bind_sweep.cpp: sweep()
void bind_atlas(py::module_& m);       // bind_atlas.cpp: equilibria(), bifurcation(), region(), region_cells(), poincare()
void bind_indicators(py::module_& m);  // bind_indicators.cpp: indicators(), tangent_flow()
void bind_spectral(py::module_& m);    // bind_spectral.cpp: spectral_statistics()
void bind_quantum(py::module_& m);     // bind_quantum.cpp: quantum_spectrum()
void bind_periodic(py::module_& m);    // bind_periodic.cpp: periodic_orbit(), continue_family()
void bind_frequencies(py::module_& m);  // bind_frequencies.cpp: frequencies()

/// lgi.Scene: a scene as read by the command line's scene reader (shared, immutable).
struct PyScene {
  std::shared_ptr<const system::Scene> scene;
};

/// A scene argument: an lgi.Scene or the path of a scene file.
std::shared_ptr<const system::Scene> scene_argument(const py::object& obj);

/// The registry's entry for a scheme name; ValueError with the CLI's message otherwise.
const integrators::SchemeInfo& scheme_argument(const std::string& name);

/// A Python dict (nested dicts: tables; lists of dicts: arrays of tables;
/// NumPy arrays through tolist()) as TOML text.
std::string toml_text_from_dict(const py::dict& d);

/// A state as a dict {R (3, 3), Pi (3,)} (copies), and back: R may be given as
/// gamma (3,) instead (the attitude of experiments/io/gamma_attitude.hpp);
/// ValueError on anything else, on an R that is not a rotation to 1e-12 and
/// on a zero gamma (bind_indicators.cpp).
py::dict state_dict(const system::State& x);
system::State state_from_dict(const py::dict& d);

/// The folder of the compiled extension (_lgi*.so), found through dladdr.
std::string extension_path();

/// A NumPy array that takes over a vector's buffer (no copy): the vector
/// lives on the heap, owned by a capsule that the array keeps alive.
template <class T>
py::array_t<T> to_numpy(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(std::move(shape), owned->data(), owner);
}

/// A scene's optional number ([run] dt, tol, t_end, the mass) as a float, or None.
inline py::object optional_number(const std::optional<double>& x) {
  return x ? py::object(py::float_(*x)) : py::none();
}

}  // namespace lgi::python

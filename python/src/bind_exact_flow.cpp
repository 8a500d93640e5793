// lgi.exact_free_flow(): the exact flow of the free rigid body
// (integrators/system/free_body_exact.hpp, the flow the scheme `exact` evaluates)
// at given times from a scene's initial state.
#include <cmath>
#include <string>

#include "integrators/system/free_body_exact.hpp"
#include "python/src/bindings.hpp"

namespace lgi::python {
namespace {

py::tuple exact_free_flow(const py::object& scene_arg, const py::array_t<double, py::array::c_style | py::array::forcecast>& times) {
  const std::shared_ptr<const system::Scene> scene = scene_argument(scene_arg);
  const system::AnyModel model = system::make_model(*scene);
  if (const std::string why = integrators::support_refusal(integrators::SceneSupport::free_body_only, model);
      !why.empty())
    throw py::value_error("exact_free_flow: the exact flow " + why + "; scene " + scene->file + " is not one");
  if (times.ndim() > 1) throw py::value_error("times: expected a number or a 1-d array of times");
  const auto n = static_cast<py::ssize_t>(times.size());
  std::vector<double> t(times.data(), times.data() + n), R(static_cast<std::size_t>(9 * n)),
      Pi(static_cast<std::size_t>(3 * n));
  // A NaN or infinite time has no state: refused, not returned as NaN (issue 50).
  for (std::size_t i = 0; i < t.size(); ++i)
    if (!std::isfinite(t[i])) throw py::value_error("times: element " + std::to_string(i) + " is not a finite number");
  {
    const py::gil_scoped_release release;
    const system::FreeBodyExactFlow flow(std::get<system::FreeBody>(model).inertia, scene->initial);
    for (std::size_t i = 0; i < t.size(); ++i) {
      const lie::SO3xR3 x = flow.at(t[i]);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) R[9 * i + static_cast<std::size_t>(3 * r + c)] = x.R(r, c);
      for (int k = 0; k < 3; ++k) Pi[3 * i + static_cast<std::size_t>(k)] = x.Pi[k];
    }
  }
  return py::make_tuple(to_numpy(std::move(R), {n, 3, 3}), to_numpy(std::move(Pi), {n, 3}));
}

}  // namespace

void bind_exact_flow(py::module_& m) {
  m.def("exact_free_flow", &exact_free_flow, py::arg("scene"), py::arg("times"),
        "exact_free_flow(scene, times) -> (R, Pi): the exact free-body flow (Jacobi elliptic functions for\n"
        "Pi, an elliptic integral of the third kind for R; Celledoni, Fasso, Safstrom & Zanna 2008) from\n"
        "the scene's initial state at t = 0, at each of `times` (s): R with shape (n, 3, 3), body -> space,\n"
        "and Pi (n, 3). ValueError if the scene declares a torque (not a free body) or a time is not finite.");
}

}  // namespace lgi::python

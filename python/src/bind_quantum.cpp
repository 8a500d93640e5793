// lgi.quantum_spectrum(): the levels of `lgi quantum` (experiments/QUANTUM.md,
// analysis/quantum/quantum_spectrum.hpp) as NumPy arrays, the same columns as
// the file's /spectrum group, with the run's facts beside them.
#include <pybind11/stl.h>

#include <cmath>
#include <string>

#include "experiments/analysis/quantum/ebk_free_rotor.hpp"
#include "experiments/analysis/quantum/ebk_kovalevskaya.hpp"
#include "experiments/analysis/quantum/quantum_spectrum.hpp"
#include "experiments/analysis/quantum/weyl_law.hpp"
#include "python/src/bindings.hpp"

namespace lgi::python {
namespace {

/// The optional columns: Weyl's smooth count at each level, the EBK levels.
void add_semiclassics(py::dict& d, const system::Scene& scene, const experiments::quantum::QuantumSpectrum& q,
                      double hbar, int m, bool weyl, bool ebk) {
  namespace eq = experiments::quantum;
  const auto rows = static_cast<py::ssize_t>(q.levels.size());
  if (weyl) {
    std::vector<double> count;
    if (q.top.is_free()) {
      for (const auto& l : q.levels) count.push_back(eq::free_rotor_weyl_count(q.top.moments, hbar, l.j, l.energy));
    } else {
      const eq::WeylCounting w(q.top, hbar, m);
      for (const auto& l : q.levels) count.push_back(w(l.energy));
    }
    d["weyl_count"] = to_numpy(std::move(count), {rows});
  }
  if (ebk) {
    std::vector<std::int64_t> n, n_fast;
    std::vector<double> energy;
    try {
      std::vector<eq::EbkRow> table;
      if (!q.top.is_free() && q.top.symmetry != eq::TopSymmetry::symmetric_heavy && eq::is_kovalevskaya_scene(scene)) {
        eq::KovalevskayaEbkOptions options;
        options.torus.dt = scene.dt.value_or(1e-2);
        const py::gil_scoped_release release;
        table = eq::ebk_kovalevskaya_table(scene, q, hbar, m, options);
      } else {
        table = eq::ebk_table(q, hbar, m);
      }
      for (const eq::EbkRow& r : table) n.push_back(r.n), n_fast.push_back(r.n_fast), energy.push_back(r.energy_ebk);
    } catch (const std::invalid_argument& e) {
      throw py::value_error(e.what());
    }
    d["ebk_n"] = to_numpy(std::move(n), {rows});
    d["ebk_n_fast"] = to_numpy(std::move(n_fast), {rows});
    d["energy_ebk"] = to_numpy(std::move(energy), {rows});
  }
}

py::dict quantum_spectrum(const py::object& scene_arg, double hbar, int m, int jmax, int levels, int jmax_step,
                          double tol, bool weyl, bool ebk) {
  const std::shared_ptr<const system::Scene> scene = scene_argument(scene_arg);
  const experiments::quantum::QuantumTop top = experiments::quantum::quantum_top_of(*scene);  // ValueError if refused
  experiments::quantum::QuantumSettings s;
  s.hbar = hbar, s.m = m, s.jmax = jmax, s.levels = levels, s.jmax_step = jmax_step, s.tol = tol;
  experiments::quantum::QuantumSpectrum q;
  try {
    const py::gil_scoped_release release;
    q = experiments::quantum::quantum_spectrum(top, s);
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
  const std::size_t n = q.levels.size();
  std::vector<std::int64_t> index(n), j(n), mm(n, m), k(n), parity(n), converged(n), k_conserved(n);
  std::vector<double> energy(n), change(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& l = q.levels[i];
    index[i] = static_cast<std::int64_t>(i), energy[i] = l.energy, j[i] = l.j, k[i] = l.k, parity[i] = l.parity;
    converged[i] = l.converged ? 1 : 0, change[i] = l.change_with_jmax, k_conserved[i] = l.k_conserved ? 1 : 0;
  }
  const auto rows = static_cast<py::ssize_t>(n);
  py::dict d;
  d["index"] = to_numpy(std::move(index), {rows});
  d["energy"] = to_numpy(std::move(energy), {rows});
  d["j"] = to_numpy(std::move(j), {rows});
  d["m"] = to_numpy(std::move(mm), {rows});
  d["k"] = to_numpy(std::move(k), {rows});
  d["parity"] = to_numpy(std::move(parity), {rows});
  d["converged"] = to_numpy(std::move(converged), {rows});
  d["change_with_jmax"] = to_numpy(std::move(change), {rows});
  d["k_conserved"] = to_numpy(std::move(k_conserved), {rows});
  d["symmetry"] = experiments::quantum::symmetry_name(q.top.symmetry);
  d["parity_classes"] = q.parity_classes;
  d["moments"] = to_numpy(std::vector<double>(q.top.moments.data(), q.top.moments.data() + 3), {3});
  d["weight"] = to_numpy(std::vector<double>(q.top.weight.data(), q.top.weight.data() + 3), {3});
  d["dimension"] = q.dimension;
  d["method"] = q.method;
  add_semiclassics(d, *scene, q, hbar, m, weyl, ebk);
  return d;
}

}  // namespace

void bind_quantum(py::module_& m) {
  m.def("quantum_spectrum", &quantum_spectrum, py::arg("scene"), py::arg("hbar"), py::arg("m") = 0,
        py::arg("jmax") = 40, py::arg("levels") = 20, py::arg("jmax_step") = 4, py::arg("tol") = 1e-8,
        py::arg("weyl") = false, py::arg("ebk") = false,
        "quantum_spectrum(scene, hbar, m=0, jmax=40, levels=20, jmax_step=4, tol=1e-8, weyl=False, ebk=False)\n"
        "-> dict: the levels of\n"
        "`lgi quantum` (experiments/QUANTUM.md): the /spectrum columns index, energy, j, m, k, parity,\n"
        "converged, change_with_jmax, k_conserved as arrays, and symmetry, parity_classes, moments and\n"
        "weight (the frame's J and c), dimension, method. ValueError for a scene term that is not a\n"
        "potential of Gamma and for settings out of range. weyl=True adds weyl_count (Weyl's smooth count at\n"
        "each level, the file's /weyl); ebk=True adds ebk_n, ebk_n_fast and energy_ebk (the file's /ebk; a\n"
        "Lagrange top, a free body or a Kovalevskaya top, ValueError otherwise), docs/quantum.md sections 7-10.");
}

}  // namespace lgi::python

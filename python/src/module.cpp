// PYBIND11_MODULE(_lgi): the compiled part of the package lgi (python/lgi/__init__.py
// re-exports it). The command line's exceptions become Python's: bad input
// (InputError, UsageError, RunError for a scheme that does not apply) raises
// ValueError and a file that cannot be written OSError, each with the message
// lgi prints after "lgi: ".
#include <dlfcn.h>

#include <filesystem>

#include "experiments/errors/exit_status.hpp"
#include "experiments/errors/input_error.hpp"
#include "experiments/io/h5md_writer.hpp"
#include "python/src/bindings.hpp"

namespace lgi::python {
namespace {

void translate_exceptions() {
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const experiments::InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const experiments::UsageError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const experiments::RunError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const experiments::OutputFileError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    }
  });
}

}  // namespace

std::string extension_path() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&extension_path), &info) == 0 || !info.dli_fname) return {};
  return std::filesystem::absolute(info.dli_fname).string();
}

}  // namespace lgi::python

PYBIND11_MODULE(_lgi, m) {
  namespace lp = lgi::python;
  m.doc() = "Lie-group integrators for rigid-body dynamics on SO(3) x R^3 (the compiled part of lgi).";
  lp::translate_exceptions();
  lp::bind_catalog(m);
  lp::bind_scene(m);
  lp::bind_simulate(m);
  lp::bind_stepper(m);
  lp::bind_exact_flow(m);
  lp::bind_sweep(m);
  lp::bind_atlas(m);
  lp::bind_indicators(m);
  lp::bind_spectral(m);
  lp::bind_quantum(m);
  lp::bind_periodic(m);
  lp::bind_frequencies(m);
}

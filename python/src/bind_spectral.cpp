// lgi.spectral_statistics(): the spectral statistics of a list of levels
// (experiments/analysis/spectral/, docs/spectral_statistics.md) as a dict,
// per symmetry class when labels are given, with the Poisson and GOE
// reference values at the same lengths and spacings.
#include <pybind11/stl.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "experiments/analysis/spectral/reference_curves.hpp"
#include "experiments/analysis/spectral/spectral_statistics.hpp"
#include "python/src/bindings.hpp"

namespace lgi::python {
namespace {

namespace sp = experiments::spectral;
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::vector<double> values_of(const std::vector<sp::WindowStatistic>& w, double sp::WindowStatistic::*field) {
  std::vector<double> out;
  for (const sp::WindowStatistic& s : w) out.push_back(s.*field);
  return out;
}

py::array_t<double> numpy(std::vector<double> v) {
  const auto n = static_cast<py::ssize_t>(v.size());
  return to_numpy(std::move(v), {n});
}

py::dict statistics_dict(const sp::SpectralStatistics& st, const sp::StatisticsOptions& o) {
  py::dict d;
  d["levels"] = st.levels;
  d["spacings"] = numpy(st.spacings);
  py::dict h;
  h["bin_width"] = st.histogram.bin_width;
  h["centres"] = numpy(st.histogram.centres);
  h["density"] = numpy(st.histogram.density);
  h["density_error"] = numpy(st.histogram.density_error);
  std::vector<std::int64_t> counts(st.histogram.counts.begin(), st.histogram.counts.end());
  const auto bins = static_cast<py::ssize_t>(counts.size());
  h["counts"] = to_numpy(std::move(counts), {bins});
  h["above"] = st.histogram.above;
  d["histogram"] = h;
  py::dict b;
  b["beta"] = st.brody.beta;
  b["standard_error"] = st.brody.standard_error;
  b["log_likelihood"] = st.brody.log_likelihood;
  b["bound"] = st.brody.bound;
  d["brody"] = b;
  d["lengths"] = numpy(o.lengths);
  d["number_variance"] = numpy(values_of(st.number_variance, &sp::WindowStatistic::value));
  d["number_variance_error"] = numpy(values_of(st.number_variance, &sp::WindowStatistic::standard_error));
  d["rigidity"] = numpy(values_of(st.rigidity, &sp::WindowStatistic::value));
  d["rigidity_error"] = numpy(values_of(st.rigidity, &sp::WindowStatistic::standard_error));
  std::vector<double> p_s, w_s, p_n, g_n, p_d, g_d;
  for (double s : st.histogram.centres) {
    p_s.push_back(sp::poisson_spacing_density(s));
    w_s.push_back(sp::wigner_spacing_density(s));
  }
  for (double l : o.lengths) {
    p_n.push_back(sp::poisson_number_variance(l)), g_n.push_back(sp::goe_number_variance(l));
    p_d.push_back(sp::poisson_rigidity(l)), g_d.push_back(sp::goe_rigidity(l));
  }
  py::dict poisson, goe;
  poisson["density"] = numpy(p_s), poisson["number_variance"] = numpy(p_n), poisson["rigidity"] = numpy(p_d);
  goe["density"] = numpy(w_s), goe["number_variance"] = numpy(g_n), goe["rigidity"] = numpy(g_d);
  d["poisson"] = poisson;
  d["goe"] = goe;
  return d;
}

py::dict spectral_statistics(const py::object& levels_arg, const py::object& classes_arg, bool unfolded,
                             std::optional<std::vector<double>> lengths, double bin_width, double s_max, int degree) {
  const Array a = Array::ensure(levels_arg);
  if (!a || a.ndim() != 1) throw py::value_error("levels: expected a one-dimensional array of numbers");
  std::vector<double> levels(a.data(), a.data() + a.size());
  sp::StatisticsOptions o;
  if (lengths) o.lengths = *lengths;
  for (double l : o.lengths)
    if (!(l > 0)) throw py::value_error("lengths: every window length must be a positive number");
  o.bin_width = bin_width, o.s_max = s_max, o.fit_degree = degree;
  std::vector<int> classes;
  if (classes_arg.is_none()) {
    classes.assign(levels.size(), 0);
  } else {
    classes = classes_arg.cast<std::vector<int>>();
  }
  // Already unfolded: the counting function is the identity.
  const sp::ClassCounting identity = [](int, double x) { return x; };
  std::vector<sp::ClassStatistics> per_class;
  {
    const py::gil_scoped_release release;
    per_class = sp::statistics_by_class(levels, classes, unfolded ? identity : sp::ClassCounting{}, o);
  }
  py::dict out;
  for (const sp::ClassStatistics& c : per_class) {
    py::dict d;
    if (c.too_few) {
      d["levels"] = c.statistics.levels;
    } else {
      d = statistics_dict(c.statistics, o);
    }
    d["too_few"] = c.too_few;
    out[py::int_(c.label)] = d;
  }
  if (classes_arg.is_none()) {
    if (per_class.empty() || per_class.front().too_few)
      throw py::value_error("levels: " + std::to_string(levels.size()) + " levels are too few");
    return out[py::int_(0)].cast<py::dict>();
  }
  return out;
}

}  // namespace

void bind_spectral(py::module_& m) {
  m.def("spectral_statistics", &spectral_statistics, py::arg("levels"), py::arg("classes") = py::none(),
        py::arg("unfolded") = false, py::arg("lengths") = py::none(), py::arg("bin_width") = sp::kDefaultBinWidth,
        py::arg("s_max") = sp::kDefaultSpacingMax, py::arg("degree") = sp::kDefaultFitDegree,
        R"(Spectral statistics of levels (docs/spectral_statistics.md).

levels: 1-d array, any order. unfolded=True: the levels are already unfolded
(e.g. by Weyl's law, preferred); else each class is unfolded by a least-squares
polynomial of `degree` through its staircase. classes: one integer label per
level; statistics are computed per class (mixing classes fakes Poisson).
Returns a dict (or, with classes, {label: dict}) with levels, spacings (mean 1),
histogram {bin_width, centres, density, density_error, counts, above},
brody {beta, standard_error, log_likelihood, bound (-1 at 0, +1 at 1)},
lengths, number_variance(_error), rigidity(_error) (Dyson-Mehta Delta3), and
the references poisson and goe {density, number_variance, rigidity}; a class
with too few levels has only levels and too_few=True. ValueError on bad input.)");
}

}  // namespace lgi::python

#include "experiments/io/poincare_file.hpp"

#include <hdf5.h>

#include <cmath>
#include <cstdlib>

#include "experiments/errors/input_error.hpp"
#include "experiments/io/hdf5_support.hpp"
#include "experiments/io/input_file.hpp"

namespace lgi::experiments {

namespace {

using hdf5::Handle;

/// A dataset of /events as n×width values of the memory type (float64 or int64).
template <class T>
std::vector<T> read_column(hid_t events, const std::string& path, const char* name, int width, hid_t memory) {
  const std::string where = path + ": /events/" + name;
  if (H5Lexists(events, name, H5P_DEFAULT) <= 0) throw InputError(where + ": missing (not a file of lgi poincare?)");
  Handle d(H5Dopen2(events, name, H5P_DEFAULT), H5Dclose);
  Handle space(d.valid() ? H5Dget_space(d.get()) : -1, H5Sclose);
  hsize_t dims[2] = {0, 1};
  const int rank = space.valid() ? H5Sget_simple_extent_ndims(space.get()) : -1;
  if (rank != (width > 1 ? 2 : 1) || H5Sget_simple_extent_dims(space.get(), dims, nullptr) != rank ||
      (width > 1 && dims[1] != static_cast<hsize_t>(width)))
    throw InputError(where + ": expected " + (width > 1 ? "n x " + std::to_string(width) : "n") + " values");
  std::vector<T> out(static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(width));
  if (!out.empty() && H5Dread(d.get(), memory, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
    throw InputError(where + ": cannot read");
  return out;
}

double number(hid_t parameters, const std::string& path, const char* name) {
  const std::string where = path + ": /parameters " + name;
  if (H5Aexists(parameters, name) <= 0) throw InputError(where + ": missing (not a file of lgi poincare?)");
  // A Cardan top's file writes its parameters as text (format_general, 17 digits: the double exactly).
  if (const auto text = hdf5::read_string_attribute(parameters, name)) {
    char* end = nullptr;
    const double v = std::strtod(text->c_str(), &end);
    if (text->empty() || end != text->c_str() + text->size() || !std::isfinite(v))
      throw InputError(where + ": expected one finite number, got '" + *text + "'");
    return v;
  }
  Handle a(H5Aopen(parameters, name, H5P_DEFAULT), H5Aclose);
  Handle space(a.valid() ? H5Aget_space(a.get()) : -1, H5Sclose);
  double v = NAN;
  if (!space.valid() || H5Sget_simple_extent_npoints(space.get()) != 1 ||
      H5Aread(a.get(), H5T_NATIVE_DOUBLE, &v) < 0 || !std::isfinite(v))
    throw InputError(where + ": expected one finite number");
  return v;
}

std::vector<lie::Vec3> vectors(const std::vector<double>& flat) {
  std::vector<lie::Vec3> v;
  for (std::size_t i = 0; i + 2 < flat.size(); i += 3) v.emplace_back(flat[i], flat[i + 1], flat[i + 2]);
  return v;
}

}  // namespace

PoincareFile read_poincare_file(const std::string& path) {
  // A FIFO would block in H5Fopen, a device or non-HDF5 file reach the library: checked first (input_file.hpp).
  if (const std::string why = hdf5_input_problem(path); !why.empty()) throw InputError(path + ": " + why);
  const hdf5::QuietHdf5Errors quiet;
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.valid()) throw InputError(path + ": cannot open as HDF5");
  if (H5Lexists(file.get(), "parameters", H5P_DEFAULT) <= 0 || H5Lexists(file.get(), "events", H5P_DEFAULT) <= 0)
    throw InputError(path + ": no /parameters and /events (not a file of lgi poincare)");
  Handle par(H5Oopen(file.get(), "parameters", H5P_DEFAULT), H5Oclose);
  Handle events(H5Gopen2(file.get(), "events", H5P_DEFAULT), H5Gclose);
  if (!par.valid() || !events.valid()) throw InputError(path + ": cannot open /parameters and /events");
  const auto subcommand = hdf5::read_string_attribute(par.get(), "subcommand");
  if (subcommand != "poincare")
    throw InputError(path + ": /parameters subcommand is '" + subcommand.value_or("") + "', not poincare");
  PoincareFile f;
  f.l = number(par.get(), path, "l");
  f.h = number(par.get(), path, "h");
  f.scene_toml = hdf5::read_string_attribute(par.get(), "scene_toml").value_or("");
  f.cardan = hdf5::read_string_attribute(par.get(), "system").value_or("") == "cardan (T^3)";
  if (f.cardan) {
    f.section = "cardan";
    f.cardan_angles = vectors(read_column<double>(events.get(), path, "cardan_angles", 3, H5T_NATIVE_DOUBLE));
    f.cardan_momenta = vectors(read_column<double>(events.get(), path, "cardan_momenta", 3, H5T_NATIVE_DOUBLE));
    f.piece = read_column<std::int64_t>(events.get(), path, "piece", 1, H5T_NATIVE_INT64);
    f.direction = read_column<std::int64_t>(events.get(), path, "direction", 1, H5T_NATIVE_INT64);
    f.orbit = read_column<std::int64_t>(events.get(), path, "index", 1, H5T_NATIVE_INT64);
    const std::size_t n = f.piece.size();
    if (f.cardan_angles.size() != n || f.cardan_momenta.size() != n || f.direction.size() != n || f.orbit.size() != n)
      throw InputError(path + ": the /events columns have different numbers of rows");
    return f;
  }
  f.axis = lie::Vec3(number(par.get(), path, "axis_1"), number(par.get(), path, "axis_2"),
                     number(par.get(), path, "axis_3"));
  f.section = hdf5::read_string_attribute(par.get(), "section").value_or("");
  if (f.section != "richter" && !f.section.starts_with("gamma"))
    throw InputError(path + ": /parameters section '" + f.section + "' is not richter or gamma*");
  f.angular_momentum = vectors(read_column<double>(events.get(), path, "angular_momentum", 3, H5T_NATIVE_DOUBLE));
  f.gamma = vectors(read_column<double>(events.get(), path, "gamma", 3, H5T_NATIVE_DOUBLE));
  f.direction = read_column<std::int64_t>(events.get(), path, "direction", 1, H5T_NATIVE_INT64);
  f.orbit = read_column<std::int64_t>(events.get(), path, "index", 1, H5T_NATIVE_INT64);
  const std::size_t n = f.gamma.size();
  if (f.angular_momentum.size() != n || f.direction.size() != n || f.orbit.size() != n)
    throw InputError(path + ": the /events columns have different numbers of rows");
  return f;
}

}  // namespace lgi::experiments

#include "experiments/io/state_file.hpp"

#include <hdf5.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <sstream>

#include "experiments/errors/input_error.hpp"
#include "experiments/io/gamma_attitude.hpp"
#include "experiments/io/hdf5_support.hpp"
#include "experiments/io/input_file.hpp"

namespace lgi::experiments {

namespace {

using hdf5::Handle;

/// The rows of an n×3 dataset, or nothing if `group` has no such dataset.
bool read_vectors(hid_t group, const char* name, std::vector<lie::Vec3>& out) {
  if (H5Lexists(group, name, H5P_DEFAULT) <= 0) return false;
  Handle d(H5Dopen2(group, name, H5P_DEFAULT), H5Dclose);
  if (!d.valid()) return false;
  Handle space(H5Dget_space(d.get()), H5Sclose);
  hsize_t dims[2] = {0, 0};
  if (!space.valid() || H5Sget_simple_extent_ndims(space.get()) != 2 ||
      H5Sget_simple_extent_dims(space.get(), dims, nullptr) != 2 || dims[1] != 3)
    return false;
  Handle type(H5Dget_type(d.get()), H5Tclose);
  if (!type.valid() || H5Tget_class(type.get()) != H5T_FLOAT) return false;
  std::vector<double> flat(static_cast<std::size_t>(dims[0]) * 3);
  if (!flat.empty() && H5Dread(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, flat.data()) < 0)
    return false;
  out.clear();
  for (std::size_t i = 0; i < flat.size(); i += 3) out.emplace_back(flat[i], flat[i + 1], flat[i + 2]);
  return true;
}

StateRows read_hdf5(const std::string& path) {
  const hdf5::QuietHdf5Errors quiet;
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.valid()) throw InputError(path + ": cannot open as HDF5");
  H5G_info_t info{};
  if (H5Gget_info(file.get(), &info) < 0) throw InputError(path + ": cannot list the groups of the file");
  std::vector<std::string> found;
  StateRows chosen;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    char name[256] = {};
    if (H5Lget_name_by_idx(file.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, name, sizeof name, H5P_DEFAULT) < 0)
      continue;
    Handle g(H5Gopen2(file.get(), name, H5P_DEFAULT), H5Gclose);  // not a group (a dataset): skipped
    StateRows r;
    if (!g.valid() || !read_vectors(g.get(), "angular_momentum", r.angular_momentum) ||
        !read_vectors(g.get(), "gamma", r.gamma))
      continue;
    if (r.angular_momentum.size() != r.gamma.size())
      throw InputError(path + ": /" + name + ": angular_momentum has " + std::to_string(r.angular_momentum.size()) +
                       " rows but gamma " + std::to_string(r.gamma.size()));
    r.source = std::string("/") + name;
    found.push_back(r.source);
    if (found.size() == 1 || r.source == "/equilibria") chosen = std::move(r);
  }
  if (found.empty())
    throw InputError(path + ": no group with the datasets angular_momentum (n x 3) and gamma (n x 3)");
  if (found.size() > 1 && chosen.source != "/equilibria") {
    std::string list;
    for (const auto& f : found) list += (list.empty() ? "" : ", ") + f;
    throw InputError(path + ": several groups have angular_momentum and gamma (" + list + "); give one table");
  }
  return chosen;
}

/// The (q, p) rows of a group, or nothing if it has neither pair of datasets.
bool read_cardan_group(hid_t g, std::vector<lie::Vec3>& q, std::vector<lie::Vec3>& p) {
  return (read_vectors(g, "cardan_angles", q) && read_vectors(g, "cardan_momenta", p)) ||
         (read_vectors(g, "initial_cardan_angles", q) && read_vectors(g, "initial_cardan_momenta", p));
}

/// The fields of one CSV line (double quotes around a field, "" inside it).
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') out.back() += '"', ++i;
    else if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) out.emplace_back();
    else if (c != '\r') out.back() += c;
  }
  return out;
}

double csv_value(const std::string& path, std::size_t line, const std::string& column, const std::string& field) {
  std::size_t begin = field.find_first_not_of(' '), end = field.find_last_not_of(' ');
  const std::string text = begin == std::string::npos ? "" : field.substr(begin, end - begin + 1);
  double x = 0.0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), x);
  if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size() || !std::isfinite(x))
    throw InputError(path + ":" + std::to_string(line) + ": " + column + ": expected a finite number, got '" + text +
                     "'");
  return x;
}

StateRows read_csv(const std::string& path) {
  std::istringstream in(read_text_input(path, "the state file"));
  std::string line;
  if (!std::getline(in, line)) throw InputError(path + ": empty state file (expected a header line)");
  const std::vector<std::string> header = csv_fields(line);
  const std::string names[6] = {"angular_momentum_1", "angular_momentum_2", "angular_momentum_3",
                                "gamma_1",            "gamma_2",            "gamma_3"};
  std::size_t at[6];
  for (int k = 0; k < 6; ++k) {
    std::size_t c = 0;
    while (c < header.size() && header[c] != names[k]) ++c;
    if (c == header.size())
      throw InputError(path + ":1: no column " + names[k] +
                       " (a CSV state file needs angular_momentum_1..3 and gamma_1..3)");
    at[k] = c;
  }
  StateRows r;
  r.source = "CSV";
  for (std::size_t number = 2; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \r") == std::string::npos) continue;
    const std::vector<std::string> f = csv_fields(line);
    if (f.size() != header.size())
      throw InputError(path + ":" + std::to_string(number) + ": " + std::to_string(f.size()) + " fields, the header has " +
                       std::to_string(header.size()));
    double v[6];
    for (int k = 0; k < 6; ++k) v[k] = csv_value(path, number, names[k], f[at[k]]);
    r.angular_momentum.emplace_back(v[0], v[1], v[2]);
    r.gamma.emplace_back(v[3], v[4], v[5]);
  }
  return r;
}

}  // namespace

StateRows read_state_file(const std::string& path) {
  // HDF5 only for a regular file with its signature; anything else is read as CSV text, under the cap.
  const bool is_hdf5 = [&] {
    const hdf5::QuietHdf5Errors quiet;
    return hdf5_input_problem(path).empty() && H5Fis_hdf5(path.c_str()) > 0;
  }();
  StateRows r = is_hdf5 ? read_hdf5(path) : read_csv(path);
  if (r.gamma.empty()) throw InputError(path + ": no states (the table has no rows)");
  return r;
}

std::vector<system::TorusState> read_cardan_state_file(const std::string& path) {
  const hdf5::QuietHdf5Errors quiet;
  if (const std::string why = hdf5_input_problem(path); !why.empty())
    throw InputError(path + ": " + why + " (a Cardan state file is HDF5: lgi chaos-map's or lgi indicators' output)");
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  H5G_info_t info{};
  if (!file.valid() || H5Gget_info(file.get(), &info) < 0) throw InputError(path + ": cannot open as HDF5");
  std::vector<std::string> found;
  std::vector<lie::Vec3> q, p;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    char name[256] = {};
    if (H5Lget_name_by_idx(file.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, name, sizeof name, H5P_DEFAULT) < 0)
      continue;
    Handle g(H5Gopen2(file.get(), name, H5P_DEFAULT), H5Gclose);
    std::vector<lie::Vec3> qi, pi;
    if (!g.valid() || !read_cardan_group(g.get(), qi, pi)) continue;
    found.push_back(std::string("/") + name);
    if (found.size() == 1) q = std::move(qi), p = std::move(pi);
  }
  if (found.empty())
    throw InputError(path + ": no group with the datasets cardan_angles and cardan_momenta (n x 3), or "
                            "initial_cardan_angles and initial_cardan_momenta");
  if (found.size() > 1) throw InputError(path + ": several groups hold Cardan states (" + found[0] + ", " + found[1] +
                                         "); give one table");
  if (q.size() != p.size() || q.empty())
    throw InputError(path + ": " + found[0] + ": " + std::to_string(q.size()) + " rows of angles and " +
                     std::to_string(p.size()) + " of momenta; need the same count, at least one");
  std::vector<system::TorusState> out(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) {
    if (!q[i].allFinite() || !p[i].allFinite())
      throw InputError(path + ": " + found[0] + ": row " + std::to_string(i) + ": a value is not finite");
    out[i].q = q[i], out[i].p = p[i];
  }
  return out;
}

std::vector<system::State> states_of(const StateRows& rows, const std::string& where, int& normalised) {
  std::vector<system::State> out;
  normalised = 0;
  for (std::size_t i = 0; i < rows.gamma.size(); ++i) {
    const double norm = rows.gamma[i].norm();
    if (!(norm > 0.0) || !std::isfinite(norm) || !rows.angular_momentum[i].allFinite())
      throw InputError(where + ": row " + std::to_string(i) +
                       ": gamma must be a nonzero finite vector and angular_momentum finite");
    if (!(std::abs(norm - 1.0) <= 1e-12)) ++normalised;
    out.push_back({attitude_from_gamma(rows.gamma[i] / norm), rows.angular_momentum[i]});
  }
  return out;
}

}  // namespace lgi::experiments

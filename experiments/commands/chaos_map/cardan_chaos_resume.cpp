#include "experiments/commands/chaos_map/cardan_chaos_resume.hpp"

#include <cstring>
#include <filesystem>

#include "experiments/commands/chaos_map/chaos_map_cells.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/hdf5_support.hpp"

namespace lgi::experiments {
namespace {

using hdf5::Handle;
constexpr std::size_t record = 10;  // doubles per orbit: done, drawn, megno, lyapunov, q0, p0

std::int64_t fnv1a(const std::string& s) {
  std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a 64 (Fowler, Noll, Vo)
  for (const char c : s) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
  std::int64_t out;
  std::memcpy(&out, &h, sizeof out);
  return out;
}

void pack(const CardanMapOrbit& o, std::int64_t t, std::vector<double>& out) {
  const double v[record] = {static_cast<double>(t), o.drawn ? 1.0 : 0.0, o.megno, o.lyapunov,
                            o.x0.q(0), o.x0.q(1), o.x0.q(2), o.x0.p(0), o.x0.p(1), o.x0.p(2)};
  out.insert(out.end(), v, v + record);
}

void unpack(const double* v, std::vector<CardanMapOrbit>& orbits) {
  const auto t = static_cast<std::int64_t>(v[0]);
  if (t < 0 || static_cast<std::size_t>(t) >= orbits.size()) return;
  CardanMapOrbit& o = orbits[static_cast<std::size_t>(t)];
  o.done = true, o.drawn = v[1] != 0.0, o.megno = v[2], o.lyapunov = v[3];
  o.x0.q = system::Vec3(v[4], v[5], v[6]), o.x0.p = system::Vec3(v[7], v[8], v[9]);
}

/// Dataset `name` of rows × width values as `memory_type`; false if it is
/// missing, of another shape, or shorter in storage than it claims.
template <class T>
bool read_dataset(hid_t file, const char* name, hid_t memory_type, int width, std::vector<T>& out) {
  Handle d(H5Dopen2(file, name, H5P_DEFAULT), H5Dclose);
  if (!d.valid()) return false;
  Handle s(H5Dget_space(d.get()), H5Sclose);
  const int rank = s.valid() ? H5Sget_simple_extent_ndims(s.get()) : -1;
  if (rank != (width > 1 ? 2 : 1)) return false;
  hsize_t dims[2] = {0, 1};
  H5Sget_simple_extent_dims(s.get(), dims, nullptr);
  if (rank == 2 && dims[1] != static_cast<hsize_t>(width)) return false;
  if (dims[0] > H5Dget_storage_size(d.get()) / sizeof(T) / static_cast<hsize_t>(width) + 1 || dims[0] > (1ULL << 34))
    return false;
  out.resize(static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(width));
  return out.empty() || H5Dread(d.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) >= 0;
}

/// The records of the partial file's finished orbits; empty message if read.
std::string read_partial(const std::string& path, const std::string& fingerprint, std::int64_t ics,
                         std::vector<double>& records) {
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.valid()) return "cannot read " + path + " as HDF5";
  std::vector<std::int64_t> print, cell, index;
  std::vector<double> megno, lyapunov, q, p;
  if (!read_dataset(file.get(), "/resume/fingerprint", H5T_NATIVE_INT64, 1, print) || print.size() != 1)
    return path + " has no /resume fingerprint (not a partial file of lgi chaos-map on a Cardan scene)";
  if (print[0] != fnv1a(fingerprint))
    return path + " was made by another command line (the scene, --vary, --h-range, --ics, --t-end, --dt, --seed "
                  "or --threshold differ); run it again with those, or remove the file";
  if (!read_dataset(file.get(), "/orbits/cell", H5T_NATIVE_INT64, 1, cell) ||
      !read_dataset(file.get(), "/orbits/index", H5T_NATIVE_INT64, 1, index) ||
      !read_dataset(file.get(), "/orbits/megno", H5T_NATIVE_DOUBLE, 1, megno) ||
      !read_dataset(file.get(), "/orbits/lyapunov", H5T_NATIVE_DOUBLE, 1, lyapunov) ||
      !read_dataset(file.get(), "/orbits/initial_cardan_angles", H5T_NATIVE_DOUBLE, 3, q) ||
      !read_dataset(file.get(), "/orbits/initial_cardan_momenta", H5T_NATIVE_DOUBLE, 3, p))
    return path + ": /orbits is damaged or incomplete";
  const std::size_t n = cell.size();
  if (index.size() != n || megno.size() != n || lyapunov.size() != n || q.size() != 3 * n || p.size() != 3 * n)
    return path + ": /orbits columns of different lengths";
  for (std::size_t k = 0; k < n; ++k) {
    if (index[k] < 0 || index[k] >= ics || cell[k] < 0) return path + ": /orbits row " + std::to_string(k) + " out of range";
    CardanMapOrbit o;
    o.drawn = std::isfinite(q[3 * k]), o.megno = megno[k], o.lyapunov = lyapunov[k];
    o.x0.q = system::Vec3(q[3 * k], q[3 * k + 1], q[3 * k + 2]), o.x0.p = system::Vec3(p[3 * k], p[3 * k + 1], p[3 * k + 2]);
    pack(o, cell[k] * ics + index[k], records);
  }
  return "";
}

}  // namespace

std::string chaos_map_fingerprint(const system::Scene& scene, const CardanChaosMapRequest& r) {
  return "lgi chaos-map (Cardan)\n" + scene.toml_text + "\nvary=" + r.vary + "\nh_range=" + r.h_range +
         "\nics=" + std::to_string(r.ics) + "\nt_end=" + exact_number(r.t_end) + "\ndt=" + exact_number(r.dt) +
         "\nseed=" + std::to_string(r.seed) + "\nthreshold=" + exact_number(r.threshold) + "\n";
}

TableGroup fingerprint_group(const std::string& fingerprint) {
  TableColumn c{"fingerprint", 1, true};
  c.whole.push_back(fnv1a(fingerprint));
  TableGroup g{"resume", {c}};
  g.attributes["what"] = "FNV-1a hash of what the orbits depend on; lgi chaos-map --resume compares it";
  return g;
}

void gather_orbits(std::vector<CardanMapOrbit>& orbits, SweepRanks& ranks) {
  if (ranks.size() == 1) return;
  std::vector<double> mine;
  for (std::size_t t = static_cast<std::size_t>(ranks.rank()); t < orbits.size(); t += static_cast<std::size_t>(ranks.size()))
    if (orbits[t].done) pack(orbits[t], static_cast<std::int64_t>(t), mine);
  const std::vector<double> all = ranks.gather(mine);
  for (std::size_t k = 0; k + record <= all.size(); k += record) unpack(all.data() + k, orbits);
}

std::int64_t load_partial_orbits(const std::string& partial, const std::string& fingerprint, std::int64_t ics,
                                 std::vector<CardanMapOrbit>& orbits, SweepRanks& ranks) {
  std::vector<double> records;
  std::string problem;
  if (ranks.root() && std::filesystem::exists(partial)) problem = read_partial(partial, fingerprint, ics, records);
  std::vector<char> bytes(problem.begin(), problem.end());
  ranks.broadcast(bytes);
  if (!bytes.empty()) throw UsageError("--resume: " + std::string(bytes.begin(), bytes.end()));
  bytes.resize(records.size() * sizeof(double));
  if (!records.empty()) std::memcpy(bytes.data(), records.data(), bytes.size());
  ranks.broadcast(bytes);
  records.resize(bytes.size() / sizeof(double));
  if (!records.empty()) std::memcpy(records.data(), bytes.data(), records.size() * sizeof(double));
  for (std::size_t k = 0; k + record <= records.size(); k += record) unpack(records.data() + k, orbits);
  return static_cast<std::int64_t>(records.size() / record);
}

}  // namespace lgi::experiments

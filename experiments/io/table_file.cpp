#include "experiments/io/table_file.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>

#include "experiments/io/h5md_writer.hpp"  // OutputFileError
#include "experiments/io/libm_code_path.hpp"
#include "experiments/io/results_file.hpp"  // results_csv_path
#include "experiments/io/sweep_hdf5.hpp"

namespace lgi::experiments {

namespace {

void refuse_existing(const std::string& path, bool force) {
  hdf5::check_output_target(path, force);
  hdf5::check_output_target(path + ".partial", true);
}

void write_csv(const std::string& path, const std::vector<TableColumn>& columns, std::size_t rows) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw OutputFileError("cannot create '" + path + "'");
  bool first = true;
  for (const auto& c : columns)
    for (int k = 0; k < c.width; ++k) {
      out << (first ? "" : ",") << c.name;
      if (c.width > 1) out << '_' << k + 1;
      first = false;
    }
  out << '\n';
  for (std::size_t r = 0; r < rows; ++r) {
    first = true;
    for (const auto& c : columns)
      for (int k = 0; k < c.width; ++k) {
        const std::size_t i = r * static_cast<std::size_t>(c.width) + static_cast<std::size_t>(k);
        out << (first ? "" : ",")
            << (c.is_text ? c.text[i] : c.integer ? std::to_string(c.whole[i]) : hdf5::csv_number(c.real[i]));
        first = false;
      }
    out << '\n';
  }
  if (!out.flush()) throw OutputWriteError("cannot write '" + path + "' (kept)");
}

std::size_t rows_of(const TableColumn& c) {
  const std::size_t n = c.is_text ? c.text.size() : c.integer ? c.whole.size() : c.real.size();
  return n / static_cast<std::size_t>(std::max(c.width, 1));
}

/// A 1-D dataset of variable-length UTF-8 strings.
void write_text(hid_t group, const TableColumn& c, const hdf5::Fail& fail) {
  hdf5::Handle type = hdf5::vlen_string_type(false, fail);
  const auto n = static_cast<hsize_t>(c.text.size());
  hdf5::Handle space(n ? H5Screate_simple(1, &n, nullptr) : H5Screate(H5S_NULL), H5Sclose);
  hdf5::Handle d(H5Dcreate2(group, c.name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                 H5Dclose);
  std::vector<const char*> p;
  for (const auto& t : c.text) p.push_back(t.c_str());
  if (!d.valid() || (n && H5Dwrite(d.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, p.data()) < 0))
    fail("cannot write " + c.name);
}

/// Every group and /parameters into `partial` (an HDF5 file created here).
void write_groups(const std::string& partial, const std::vector<TableGroup>& groups,
                  const std::map<std::string, std::string>& parameters) {
  const hdf5::QuietHdf5Errors quiet;
  auto refuse = [&partial](const std::string& what) {
    throw OutputFileError(partial + ": " + what + " (" + hdf5::hdf5_error_detail() + ")");
  };
  // Once the file exists a failure is a failed write (exit 1; README, "exit statuses"), the file kept.
  auto fail = [&partial](const std::string& what) {
    throw OutputWriteError(partial + ": " + what + " (" + hdf5::hdf5_error_detail() + "); " + partial + " is kept");
  };
  hdf5::Handle file = hdf5::create_file(partial, refuse);
  const sweep_hdf5::SweepHdf5 h5(fail);
  for (const auto& g : groups) {
    hdf5::Handle table = hdf5::create_group(file.get(), "/" + g.name, fail);
    for (const auto& c : g.columns) {
      const auto n = static_cast<std::int64_t>(rows_of(c));
      if (c.is_text) write_text(table.get(), c, fail);
      else if (c.integer) h5.write_whole(table.get(), c.name, H5T_STD_I64LE, H5T_NATIVE_INT64, n, c.width, c.whole.data());
      else h5.write_whole(table.get(), c.name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, n, c.width, c.real.data());
    }
    for (const auto& [k, v] : g.attributes) hdf5::write_vlen_string(table.get(), k.c_str(), v, false, fail);
  }
  hdf5::Handle params = hdf5::create_group(file.get(), "/parameters", fail);
  for (const auto& [k, v] : parameters) hdf5::write_vlen_string(params.get(), k.c_str(), v, false, fail);
  if (!parameters.contains("libm")) hdf5::write_vlen_string(params.get(), "libm", libm_code_path(), false, fail);
  if (file.reset() < 0) fail("cannot close");
}

}  // namespace

void write_table_file(const std::string& path, bool force, const std::string& group,
                      const std::vector<TableColumn>& columns, const std::map<std::string, std::string>& parameters,
                      const std::vector<TableGroup>& extra_groups) {
  const std::string csv = results_csv_path(path);
  refuse_existing(path, force);
  refuse_existing(csv, force);
  const std::size_t rows = columns.empty() ? 0 : rows_of(columns[0]);
  const std::string partial = path + ".partial", csv_partial = csv + ".partial";
  std::vector<TableGroup> groups = {{group, columns}};
  groups.insert(groups.end(), extra_groups.begin(), extra_groups.end());
  write_groups(partial, groups, parameters);
  write_csv(csv_partial, columns, rows);
  hdf5::publish(partial, path, force, "the table is");
  hdf5::publish(csv_partial, csv, force, "the table is");
}

void write_groups_file(const std::string& path, bool force, const std::vector<TableGroup>& groups,
                       const std::map<std::string, std::string>& parameters) {
  refuse_existing(path, force);
  const std::string partial = path + ".partial";
  write_groups(partial, groups, parameters);
  hdf5::publish(partial, path, force, "the table is");
}

}  // namespace lgi::experiments

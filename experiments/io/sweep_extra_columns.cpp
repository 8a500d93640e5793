#include "experiments/io/sweep_extra_columns.hpp"

#include "experiments/io/h5md_writer.hpp"  // OutputFileError
#include "experiments/io/hdf5_inspection.hpp"
#include "experiments/io/sweep_hdf5.hpp"

namespace lgi::experiments {

using hdf5::Handle;

SweepExtraColumns::SweepExtraColumns(const std::string& path) : path_(path) {
  const hdf5::QuietHdf5Errors quiet;
  if (const std::string why = hdf5::inspect_in_child(path); !why.empty())
    throw OutputFileError(path_ + ": " + why + " (damaged)");
  file_ = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  if (file_ < 0) fail("cannot open for writing");
}

SweepExtraColumns::~SweepExtraColumns() {
  if (file_ >= 0) H5Fclose(file_);
}

void SweepExtraColumns::fail(const std::string& what) const {
  throw OutputFileError(path_ + ": " + what + " (" + hdf5::hdf5_error_detail() + ")");
}

std::int64_t SweepExtraColumns::rows(const std::string& group, const std::string& name) const {
  const hdf5::QuietHdf5Errors quiet;
  const sweep_hdf5::SweepHdf5 io([this](const std::string& w) { fail(w); });
  return io.rows_of(file_, ("/" + group + "/" + name).c_str());
}

std::vector<double> SweepExtraColumns::read_real(const std::string& group, const std::string& name, int width) const {
  const hdf5::QuietHdf5Errors quiet;
  const sweep_hdf5::SweepHdf5 io([this](const std::string& w) { fail(w); });
  const std::string path = "/" + group + "/" + name;
  const std::int64_t n = io.rows_of(file_, path);
  if (n < 0) fail("no dataset " + path);
  std::vector<double> v(static_cast<std::size_t>(n * width));
  io.read_rows(file_, path, H5T_NATIVE_DOUBLE, 0, n, width, v.data());
  return v;
}

std::vector<std::int64_t> SweepExtraColumns::read_integer(const std::string& group, const std::string& name) const {
  const hdf5::QuietHdf5Errors quiet;
  const sweep_hdf5::SweepHdf5 io([this](const std::string& w) { fail(w); });
  const std::string path = "/" + group + "/" + name;
  const std::int64_t n = io.rows_of(file_, path);
  if (n < 0) fail("no dataset " + path);
  std::vector<std::int64_t> v(static_cast<std::size_t>(n));
  io.read_rows(file_, path, H5T_NATIVE_INT64, 0, n, 1, v.data());
  return v;
}

void SweepExtraColumns::write_real(const std::string& group, const std::string& name,
                                   const std::vector<double>& values, int width) {
  const hdf5::QuietHdf5Errors quiet;
  const sweep_hdf5::SweepHdf5 io([this](const std::string& w) { fail(w); });
  Handle g = hdf5::open_or_create_group(file_, group, [this](const std::string& w) { fail(w); });
  io.write_whole(g.get(), name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                 static_cast<std::int64_t>(values.size()) / width, width, values.data());
}

void SweepExtraColumns::write_integer(const std::string& group, const std::string& name,
                                      const std::vector<std::int64_t>& values) {
  const hdf5::QuietHdf5Errors quiet;
  const sweep_hdf5::SweepHdf5 io([this](const std::string& w) { fail(w); });
  Handle g = hdf5::open_or_create_group(file_, group, [this](const std::string& w) { fail(w); });
  io.write_whole(g.get(), name, H5T_STD_I64LE, H5T_NATIVE_INT64, static_cast<std::int64_t>(values.size()), 1,
                 values.data());
}

void SweepExtraColumns::close() {
  if (file_ >= 0) {
    const herr_t r = H5Fclose(file_);
    file_ = -1;
    if (r < 0) fail("cannot close");
  }
}

}  // namespace lgi::experiments

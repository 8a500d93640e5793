// Trajectory writer: H5MD 1.1 layout of experiments/OUTPUT.md, HDF5 C API.
#include "experiments/io/h5md_writer.hpp"

#include <fcntl.h>
#include <hdf5.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <limits>
#include <set>
#include <utility>

#include "experiments/io/hdf5_support.hpp"

namespace lgi::experiments {

using hdf5::create_group;
using hdf5::errno_text;
using hdf5::Handle;
using hdf5::hdf5_error_detail;
using hdf5::QuietHdf5Errors;
using hdf5::write_double_attribute;
using hdf5::write_fixed_strings;
using hdf5::write_int_attribute;
using hdf5::write_vlen_string;

std::string hdf5_library_version() {
  unsigned maj = 0, min = 0, rel = 0;
  H5get_libversion(&maj, &min, &rel);
  return std::to_string(maj) + "." + std::to_string(min) + "." + std::to_string(rel);
}

// ---- the file's open objects ---------------------------------------------------

namespace {

constexpr hsize_t unlimited = H5S_UNLIMITED;

/// One time series' value dataset (or the shared step / time datasets):
/// rank 1 + item rank, item shape item[0..rank-2].
struct Series {
  Handle dataset;
  std::string name;  // full path, for messages
  int rank = 1;
  std::array<hsize_t, 2> item{};
  hid_t memory_type = H5I_INVALID_HID;
};

}  // namespace

struct TrajectoryWriter::Impl {
  // Declaration order matters: destruction closes the datasets before the file.
  Handle file;
  Handle diagnostics;  // the /diagnostics group
  Series step, time, orientation, momentum, velocity, euler, energy, momentum_space, orthogonality;
  std::vector<Series> invariants;
};

// Thrown as OutputFileError: "cannot write trajectory '<partial>': <what>[: <HDF5 detail>]".
void TrajectoryWriter::fail(const std::string& what) const {
  std::string msg = "cannot write trajectory '" + partial_path_ + "': " + what;
  const std::string detail = hdf5_error_detail();
  if (!detail.empty()) msg += " (HDF5: " + detail + ")";
  if (created_) throw OutputWriteError(msg);
  throw OutputFileError(msg);
}

namespace {

// Helpers that need the writer's fail() receive it as a callable.
/// A chunked, extendible dataset [0][item...] with maxdims [unlimited][item...].
template <class Fail>
Series make_series(hid_t group, const char* name, const std::string& full, hid_t file_type, hid_t memory_type,
                   std::initializer_list<hsize_t> item, hsize_t chunk_rows, const char* unit, Fail&& fail) {
  Series s;
  s.name = full;
  s.rank = 1 + static_cast<int>(item.size());
  s.memory_type = memory_type;
  std::array<hsize_t, 3> dims{0, 1, 1}, maxdims{unlimited, 1, 1}, chunk{chunk_rows, 1, 1};
  std::size_t k = 0;
  for (hsize_t d : item) {
    s.item[k] = d;
    dims[k + 1] = maxdims[k + 1] = chunk[k + 1] = d;
    ++k;
  }
  Handle space(H5Screate_simple(s.rank, dims.data(), maxdims.data()), H5Sclose);
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  if (!space.valid() || !dcpl.valid() || H5Pset_chunk(dcpl.get(), s.rank, chunk.data()) < 0 ||
      H5Pset_fill_time(dcpl.get(), H5D_FILL_TIME_NEVER) < 0)
    fail("cannot set up dataset " + full);
  s.dataset = Handle(H5Dcreate2(group, name, file_type, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT), H5Dclose);
  if (!s.dataset.valid()) fail("cannot create dataset " + full);
  if (unit != nullptr && *unit != '\0') write_vlen_string(s.dataset.get(), "unit", unit, /*ascii=*/true, fail);
  return s;
}

/// Appends n rows from `data` (row-major, rows of the item shape) at row `at`.
template <class Fail>
void write_rows(const Series& s, hsize_t at, hsize_t n, const void* data, Fail&& fail) {
  std::array<hsize_t, 3> dims{at + n, s.item[0], s.item[1]};
  std::array<hsize_t, 3> start{at, 0, 0};
  std::array<hsize_t, 3> count{n, s.item[0], s.item[1]};
  const hid_t d = s.dataset.get();
  if (H5Dset_extent(d, dims.data()) < 0) fail("cannot extend " + s.name);
  Handle file_space(H5Dget_space(d), H5Sclose);
  Handle memory_space(H5Screate_simple(s.rank, count.data(), nullptr), H5Sclose);
  if (!file_space.valid() || !memory_space.valid() ||
      H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr) < 0)
    fail("cannot select rows of " + s.name);
  if (H5Dwrite(d, s.memory_type, memory_space.get(), file_space.get(), H5P_DEFAULT, data) < 0)
    fail("cannot write " + s.name);
}

template <class Fail>
void hard_link(hid_t file, const std::string& target, hid_t group, const char* name, Fail&& fail) {
  if (H5Lcreate_hard(file, target.c_str(), group, name, H5P_DEFAULT, H5P_DEFAULT) < 0)
    fail("cannot link " + target);
}

void validate_layout(const TrajectoryLayout& layout, const WriterOptions& options) {
  if (layout.scalar_invariants.size() > max_scalar_invariants)
    throw std::invalid_argument("trajectory layout: " + std::to_string(layout.scalar_invariants.size()) +
                                " scalar invariants, at most " + std::to_string(max_scalar_invariants));
  std::set<std::string> names{"energy", "orthogonality_error", "angular_momentum_space"};
  for (const auto& s : layout.scalar_invariants) {
    if (s.name.empty() || s.name == "." || s.name == ".." || s.name.find('/') != std::string::npos)
      throw std::invalid_argument("trajectory layout: bad observable name '" + s.name + "'");
    if (!names.insert(s.name).second)
      throw std::invalid_argument("trajectory layout: observable name '" + s.name + "' used twice or reserved");
  }
  if (options.block_size == 0 || options.chunk_rows == 0)
    throw std::invalid_argument("trajectory writer: block_size and chunk_rows must be positive");
  if (!(options.flush_interval_seconds >= 0.0))
    throw std::invalid_argument("trajectory writer: flush_interval_seconds must be >= 0");
}

/// A series whose group sits at `full` and shares the orientation's step and time.
template <class Fail>
Series linked_series(hid_t f, const std::string& full, std::initializer_list<hsize_t> item, hsize_t rows,
                     const char* unit, Fail&& fail) {
  Handle grp = create_group(f, full, fail);
  hard_link(f, "/particles/body/orientation/step", grp.get(), "step", fail);
  hard_link(f, "/particles/body/orientation/time", grp.get(), "time", fail);
  return make_series(grp.get(), "value", full + "/value", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, item, rows, unit, fail);
}

/// /parameters: the caller's attributes plus the default provenance.
template <class Fail>
void write_parameters_group(hid_t f, const Provenance& provenance, Fail&& fail) {
  Handle params = create_group(f, "/parameters", fail);
  std::map<std::string, std::string> text = provenance.text_attributes;
  auto add_default = [&](const std::string& key, const std::string& value) {
    if (!text.count(key) && !provenance.number_attributes.count(key) && !provenance.integer_attributes.count(key))
      text[key] = value;
  };
  for (const auto& [k, v] : hdf5::default_provenance(hdf5::utc_now_iso8601())) add_default(k, v);
  for (const auto& [k, v] : text) write_vlen_string(params.get(), k.c_str(), v, false, fail);
  for (const auto& [k, v] : provenance.number_attributes) write_double_attribute(params.get(), k.c_str(), v, fail);
  for (const auto& [k, v] : provenance.integer_attributes)
    write_int_attribute(params.get(), k.c_str(), H5T_STD_I64LE, v, fail);
}

/// Refuses before touching anything; creates `partial` with plain POSIX (clearest errno).
void create_partial_file(const std::string& path, const std::string& partial, bool force) {
  hdf5::check_output_target(path, force);
  hdf5::check_output_target(partial, true);  // a leftover .partial is replaced; never a FIFO (open would block)
  struct stat st {};
  const std::string dir = hdf5::parent_directory(path);
  if (::stat(dir.c_str(), &st) != 0)
    throw OutputFileError("cannot write trajectory '" + path + "': directory '" + dir + "': " + errno_text(errno));
  if (!S_ISDIR(st.st_mode))
    throw OutputFileError("cannot write trajectory '" + path + "': '" + dir + "' is not a directory");
  const int fd = ::open(partial.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) {
    const int err = errno;
    throw OutputFileError("cannot write trajectory '" + path + "': cannot create '" + partial +
                          "' in directory '" + dir + "': " + errno_text(err));
  }
  ::close(fd);
}

}  // namespace

// ---- construction --------------------------------------------------------------

TrajectoryWriter::TrajectoryWriter(const std::string& path, bool force, const TrajectoryLayout& layout,
                                   const Provenance& provenance, const WriterOptions& options)
    : path_(path), partial_path_(path + ".partial"), force_(force), layout_(layout), impl_(std::make_unique<Impl>()) {
  validate_layout(layout, options);
  if (path.empty()) throw OutputFileError("cannot write trajectory: empty output file name");
  create_partial_file(path, partial_path_, force);
  size_buffers(options);
  QuietHdf5Errors quiet;
  auto fail_fn = [this](const std::string& what) { fail(what); };
  try {
    impl_->file = hdf5::create_file(partial_path_, fail_fn);
    const hid_t f = impl_->file.get();
    hdf5::write_h5md_metadata(f, /*units_module=*/true, fail_fn);
    create_body(options.chunk_rows);
    create_observables(options.chunk_rows);
    write_parameters_group(f, provenance, fail_fn);
    write_running_diagnostics();
    if (H5Fflush(f, H5F_SCOPE_LOCAL) < 0) fail("cannot flush");
  } catch (...) {
    impl_.reset();  // closes datasets and groups, then the file
    ::unlink(partial_path_.c_str());
    throw;
  }
  open_ = created_ = true;
  last_flush_ = std::chrono::steady_clock::now();
}

void TrajectoryWriter::size_buffers(const WriterOptions& options) {
  block_size_ = options.block_size;
  flush_interval_ = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(options.flush_interval_seconds));
  const std::size_t b = block_size_;
  step_.resize(b);
  time_.resize(b);
  quat_.resize(4 * b);
  pi_.resize(3 * b);
  omega_.resize(3 * b);
  energy_.resize(b);
  ortho_.resize(b);
  if (layout_.space_momentum) m_space_.resize(3 * b);
  if (layout_.euler_zxz) euler_.resize(3 * b);
  invariants_.resize(layout_.scalar_invariants.size() * b);
}

// /particles/body. Groups are made by their full path, so parents need not stay open.
void TrajectoryWriter::create_body(std::size_t chunk_rows) {
  auto fail_fn = [this](const std::string& what) { fail(what); };
  const hid_t f = impl_->file.get();
  const auto rows = static_cast<hsize_t>(chunk_rows);
  create_group(f, "/particles", fail_fn);
  create_group(f, "/particles/body", fail_fn);
  Handle box = create_group(f, "/particles/body/box", fail_fn);
  write_int_attribute(box.get(), "dimension", H5T_STD_I32LE, 3, fail_fn);
  write_fixed_strings(box.get(), "boundary", {"none", "none", "none"}, false, fail_fn);
  Handle g = create_group(f, "/particles/body/orientation", fail_fn);
  impl_->step = make_series(g.get(), "step", "/particles/body/orientation/step", H5T_STD_I64LE, H5T_NATIVE_INT64,
                            {}, rows, nullptr, fail_fn);
  impl_->time = make_series(g.get(), "time", "/particles/body/orientation/time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                            {}, rows, "s", fail_fn);
  impl_->orientation = make_series(g.get(), "value", "/particles/body/orientation/value", H5T_IEEE_F64LE,
                                   H5T_NATIVE_DOUBLE, {1, 4}, rows, nullptr, fail_fn);
  impl_->momentum = linked_series(f, "/particles/body/angular_momentum_body", {1, 3}, rows, "kg m+2 s-1", fail_fn);
  impl_->velocity = linked_series(f, "/particles/body/angular_velocity_body", {1, 3}, rows, "s-1", fail_fn);
  if (layout_.euler_zxz) impl_->euler = linked_series(f, "/particles/body/euler_zxz", {1, 3}, rows, "rad", fail_fn);
}

void TrajectoryWriter::create_observables(std::size_t chunk_rows) {
  auto fail_fn = [this](const std::string& what) { fail(what); };
  const hid_t f = impl_->file.get();
  const auto rows = static_cast<hsize_t>(chunk_rows);
  create_group(f, "/observables", fail_fn);
  auto observable = [&](const std::string& name, std::initializer_list<hsize_t> item, const char* unit) {
    return linked_series(f, "/observables/" + name, item, rows, unit, fail_fn);
  };
  impl_->energy = observable("energy", {}, "kg m+2 s-2");
  if (layout_.space_momentum) impl_->momentum_space = observable("angular_momentum_space", {3}, "kg m+2 s-1");
  for (const auto& s : layout_.scalar_invariants) impl_->invariants.push_back(observable(s.name, {}, s.unit.c_str()));
  impl_->orthogonality = observable("orthogonality_error", {}, nullptr);
}

// /diagnostics: placeholders until finish/abandon (what a killed run leaves).
void TrajectoryWriter::write_running_diagnostics() {
  impl_->diagnostics = create_group(impl_->file.get(), "/diagnostics", [this](const std::string& w) { fail(w); });
  Diagnostics running;
  running.steps = running.rejected_steps = running.rhs_evaluations = -1;
  running.newton_iterations_max = running.newton_failures = -1;
  running.cpu_seconds = running.output_seconds = std::numeric_limits<double>::quiet_NaN();
  running.status = "running";
  write_diagnostics(running);
}

TrajectoryWriter::~TrajectoryWriter() {
  if (!open_) return;
  try {
    abandon_impl(nullptr, write_failed_ ? "failed: " + write_error_ : std::string("interrupted"));
  } catch (...) {  // a destructor must not throw; the .partial stays as it is
  }
}

// ---- appending -------------------------------------------------------------------

void TrajectoryWriter::append(const TrajectorySample& s) {
  if (!open_) throw std::logic_error("trajectory '" + path_ + "': append after the file was closed");
  if (write_failed_) fail("an earlier block write failed");
  if (s.invariant_count != layout_.scalar_invariants.size())
    throw std::invalid_argument("trajectory '" + path_ + "': sample has " + std::to_string(s.invariant_count) +
                                " invariants, layout has " + std::to_string(layout_.scalar_invariants.size()));
  // Samples interpolated inside one step (lgi simulate --output-dt) share its step number, at later times.
  if (have_last_ && (s.step < last_step_ || s.time < last_time_ || (s.step == last_step_ && !(s.time > last_time_))))
    throw std::invalid_argument("trajectory '" + path_ + "': sample at step " + std::to_string(s.step) + " (t = " +
                                std::to_string(s.time) + ") does not follow step " + std::to_string(last_step_) +
                                " (t = " + std::to_string(last_time_) + ")");
  have_last_ = true;
  last_step_ = s.step;
  last_time_ = s.time;

  const std::size_t i = buffered_;
  step_[i] = s.step;
  time_[i] = s.time;
  for (std::size_t c = 0; c < 4; ++c) quat_[4 * i + c] = s.quaternion_wxyz[c];
  for (Eigen::Index c = 0; c < 3; ++c) {
    const auto u = static_cast<std::size_t>(c);
    pi_[3 * i + u] = s.angular_momentum_body[c];
    omega_[3 * i + u] = s.angular_velocity_body[c];
  }
  energy_[i] = s.energy;
  ortho_[i] = s.orthogonality_error;
  if (layout_.space_momentum)
    for (Eigen::Index c = 0; c < 3; ++c) m_space_[3 * i + static_cast<std::size_t>(c)] = s.angular_momentum_space[c];
  if (layout_.euler_zxz)
    for (std::size_t c = 0; c < 3; ++c) euler_[3 * i + c] = s.euler_zxz[c];
  for (std::size_t k = 0; k < s.invariant_count; ++k) invariants_[k * block_size_ + i] = s.invariants[k];
  ++buffered_;

  if (buffered_ == block_size_ || (buffered_ & 255u) == 0) [[unlikely]]
    append_slow_path();
}

void TrajectoryWriter::append_slow_path() {
  if (buffered_ == block_size_ || std::chrono::steady_clock::now() - last_flush_ >= flush_interval_) flush();
}

void TrajectoryWriter::write_block() {
  if (buffered_ == 0) return;
  auto fail_fn = [this](const std::string& what) { fail(what); };
  const auto at = static_cast<hsize_t>(written_);
  const auto n = static_cast<hsize_t>(buffered_);
  try {
    Impl& m = *impl_;
    write_rows(m.step, at, n, step_.data(), fail_fn);
    write_rows(m.time, at, n, time_.data(), fail_fn);
    write_rows(m.orientation, at, n, quat_.data(), fail_fn);
    write_rows(m.momentum, at, n, pi_.data(), fail_fn);
    write_rows(m.velocity, at, n, omega_.data(), fail_fn);
    if (layout_.euler_zxz) write_rows(m.euler, at, n, euler_.data(), fail_fn);
    write_rows(m.energy, at, n, energy_.data(), fail_fn);
    if (layout_.space_momentum) write_rows(m.momentum_space, at, n, m_space_.data(), fail_fn);
    for (std::size_t k = 0; k < m.invariants.size(); ++k)
      write_rows(m.invariants[k], at, n, &invariants_[k * block_size_], fail_fn);
    write_rows(m.orthogonality, at, n, ortho_.data(), fail_fn);
  } catch (const std::exception& e) {
    // Datasets may now differ in length; write nothing more but diagnostics.
    write_failed_ = true;
    write_error_ = e.what();
    buffered_ = 0;
    throw;
  }
  written_ += static_cast<std::int64_t>(n);
  buffered_ = 0;
}

void TrajectoryWriter::flush() {
  if (!open_) throw std::logic_error("trajectory '" + path_ + "': flush after the file was closed");
  if (write_failed_) fail("an earlier block write failed");
  QuietHdf5Errors quiet;
  write_block();
  if (H5Fflush(impl_->file.get(), H5F_SCOPE_LOCAL) < 0) {
    write_failed_ = true;  // what reached the disk is unknown: write nothing more but diagnostics
    write_error_ = "cannot flush";
    fail("cannot flush");
  }
  last_flush_ = std::chrono::steady_clock::now();
}

// ---- closing -----------------------------------------------------------------------

void TrajectoryWriter::write_diagnostics(const Diagnostics& d) {
  auto fail_fn = [this](const std::string& what) { fail(what); };
  const hid_t g = impl_->diagnostics.get();
  write_int_attribute(g, "steps", H5T_STD_I64LE, d.steps, fail_fn);
  write_int_attribute(g, "rejected_steps", H5T_STD_I64LE, d.rejected_steps, fail_fn);
  write_int_attribute(g, "rhs_evaluations", H5T_STD_I64LE, d.rhs_evaluations, fail_fn);
  write_int_attribute(g, "newton_iterations_max", H5T_STD_I64LE, d.newton_iterations_max, fail_fn);
  write_int_attribute(g, "newton_failures", H5T_STD_I64LE, d.newton_failures, fail_fn);
  write_double_attribute(g, "cpu_seconds", d.cpu_seconds, fail_fn);
  write_double_attribute(g, "output_seconds", d.output_seconds, fail_fn);
  write_status(d.status);
}

void TrajectoryWriter::write_status(const std::string& status) {
  auto fail_fn = [this](const std::string& what) { fail(what); };
  write_vlen_string(impl_->diagnostics.get(), "status", status, false, fail_fn);
}

void TrajectoryWriter::close_file() {
  open_ = false;
  Impl& m = *impl_;
  for (Series* s : {&m.step, &m.time, &m.orientation, &m.momentum, &m.velocity, &m.euler, &m.energy,
                          &m.momentum_space, &m.orthogonality})
    s->dataset.reset();
  m.invariants.clear();
  m.diagnostics.reset();
  if (m.file.reset() < 0) fail("cannot close the HDF5 file");
}

void TrajectoryWriter::finish(const Diagnostics& diagnostics) {
  if (!open_) throw std::logic_error("trajectory '" + path_ + "': finish after the file was closed");
  QuietHdf5Errors quiet;
  write_then_close([&] {
    if (write_failed_) fail("an earlier block write failed");
    write_block();
    write_diagnostics(diagnostics);
  });
  // Without force, never replace a file that appeared during the run.
  hdf5::publish(partial_path_, path_, force_, "the trajectory is");
}

void TrajectoryWriter::abandon(const Diagnostics& diagnostics) {
  if (!open_) return;
  abandon_impl(&diagnostics, diagnostics.status);
}

void TrajectoryWriter::abandon_impl(const Diagnostics* d, const std::string& status) {
  QuietHdf5Errors quiet;
  try {
    if (!write_failed_) write_block();
  } catch (const OutputFileError&) {  // keep going: the diagnostics matter more
  }
  write_then_close([&] {
    if (d != nullptr) {
      Diagnostics copy = *d;
      copy.status = status;
      write_diagnostics(copy);
    } else {
      write_status(status);
    }
  });
}

void TrajectoryWriter::write_then_close(const std::function<void()>& last_writes) {
  try {
    last_writes();
    close_file();
  } catch (...) {
    if (open_) {
      try {
        close_file();
      } catch (...) {  // report the first failure
      }
    }
    throw;
  }
}

}  // namespace lgi::experiments

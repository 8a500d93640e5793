// libFuzzer harness: bytes -> an HDF5 file -> one of the readers of files
// lgi reads back (fuzz/h5_fixtures.hpp: the input's first byte picks it):
//   lgi sweep --resume   SweepPartialFile (resume), the rows completed, the final file written;
//   lgi poincare         SweepExtraColumns on a finished sweep file, read and extended;
//   lgi long-time --resume  the .partial reopened (ResultsFile::Reopen), its fingerprint and
//                           checkpoints read (run_checkpoint.hpp), rows kept, one appended, published.
// A damaged, truncated or foreign file must end in OutputFileError (or the
// UsageError of a fingerprint that differs) with one line naming the file,
// with HDF5's own error printing off; anything else (another exception, a
// crash, a sanitizer report, a message with a line break, HDF5 printing its
// error stack) is a finding.
#include <hdf5.h>
#include <stdlib.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "experiments/commands/long_time/long_time_resume.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/sweep_extra_columns.hpp"
#include "fuzz/h5_fixtures.hpp"

namespace {

namespace ex = lgi::experiments;
namespace fz = lgi::fuzz;
namespace fs = std::filesystem;

/// A private folder for the files of one process, made once. The name is
/// never destroyed: the exit handler that removes the folder is registered
/// before a static string's destructor would be, and so would run after it.
const std::string& folder() {
  static const std::string* const dir = [] {
    const char* base = ::access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    auto* pattern = new std::string(std::string(base) + "/lgi-fuzz-h5-XXXXXX");
    if (!::mkdtemp(pattern->data())) std::abort();
    std::atexit([] { std::error_code ec; fs::remove_all(folder(), ec); });
    return pattern;
  }();
  return *dir;
}

void write_file(const std::string& path, const std::uint8_t* data, std::size_t size) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                                 static_cast<std::streamsize>(size));
}

void sweep_resume(const std::string& partial) {
  ex::SweepPartialFile file(partial, fz::sweep_layout(), fz::sweep_fingerprint, true);
  for (std::int64_t i = 0; i < fz::sweep_layout().count; ++i)
    if (!file.done()[static_cast<std::size_t>(i)]) file.write(fz::sweep_chunk(i, 1, 1));
  file.write_final(folder() + "/sweep.h5", {});
  file.close();
}

void sweep_columns(const std::string& path) {
  ex::SweepExtraColumns file(path);
  const std::vector<double> g = file.read_real("events", "gamma", 3);
  const std::vector<double> p = file.read_real("events", "angular_momentum", 3);
  const std::vector<std::int64_t> index = file.read_integer("sweep", "index");
  (void)file.rows("sweep", "t_final");
  file.write_real("events", "phi", std::vector<double>(g.size() / 3, 0.5), 1);
  file.write_integer("sweep", "sheet", std::vector<std::int64_t>(index.size(), 1));
  file.close();
}

void long_time_resume(const std::string& out) {
  // The CSV twin as the seed's run left it: the header and more rows than the HDF5 file has.
  std::string csv = "step,time,energy_error,energy_error_window_max\n";
  for (int r = 0; r < 64; ++r) csv += std::to_string(r) + ",0.5,1e-16,1e-16\n";
  std::ofstream(folder() + "/lt.csv.partial", std::ios::trunc) << csv;
  ex::ResumedResults<lgi::system::State> r = ex::reopen_for_resume<lgi::system::State>(out, true, fz::long_time_columns(), fz::long_time_options(),
                                                                                  fz::long_time_fingerprint, 1);
  if (!r.file) return;  // no fingerprint: lgi long-time starts a new run
  ex::ResultRow row = r.file->row();
  row.set("step", r.checkpoint ? r.checkpoint->loop.step + 1 : std::int64_t{0});
  row.set("time", 1.0);
  r.file->append(row);
  r.file->finish({});
}

/// One line naming one of the harness's files.
void check_message(const std::string& m) {
  if (m.find('\n') != std::string::npos || m.find(folder()) == std::string::npos) {
    std::fprintf(stderr, "bad message: %s\n", m.c_str());
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  // lgi's readers silence HDF5's error printing (QuietHdf5Errors) around their calls and
  // turn failures into one-line errors; a failing HDF5 call outside such a scope would
  // print HDF5's error stack: a finding.
  H5Eset_auto2(H5E_DEFAULT, [](hid_t, void*) -> herr_t {
    std::fprintf(stderr, "HDF5 would print its error stack: an HDF5 call outside QuietHdf5Errors failed\n");
    std::abort();
  }, nullptr);
  const auto reader = static_cast<fz::Reader>(data[0] % fz::reader_count);
  const std::string dir = folder();
  for (const char* name : {"sweep.h5.partial", "sweep.h5", "lt.h5.partial", "lt.csv.partial", "lt.h5", "lt.csv"})
    std::remove((dir + "/" + name).c_str());
  const std::string path = dir + (reader == fz::long_time_resume ? "/lt.h5.partial" : "/sweep.h5.partial");
  write_file(path, data + 1, size - 1);
  try {
    switch (reader) {
      case fz::sweep_resume: sweep_resume(path); break;
      case fz::sweep_columns: sweep_columns(path); break;
      default: long_time_resume(dir + "/lt.h5"); break;
    }
  } catch (const ex::OutputFileError& e) {
    check_message(e.what());
  } catch (const ex::UsageError& e) {  // a fingerprint that differs: --resume refuses the file
    check_message(e.what());
  }
  return 0;
}

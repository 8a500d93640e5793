// Writes the seed corpus of fuzz/fuzz_h5_readers.cpp into a folder: one
// valid file per reader, written by lgi's own writers with the layouts of
// fuzz/h5_fixtures.hpp, each prefixed with the byte that picks its reader;
// and each truncated at eight lengths (a run killed while writing, a copy cut
// short). CMake runs it at build time (fuzz/CMakeLists.txt), so the seeds
// always match the writers.
// usage: fuzz_h5_seeds FOLDER
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "experiments/commands/long_time/long_time_resume.hpp"
#include "fuzz/h5_fixtures.hpp"

namespace {

namespace ex = lgi::experiments;
namespace fz = lgi::fuzz;
namespace fs = std::filesystem;

std::vector<char> bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The seed and its truncations, named <name>, <name>.cut<k>.
void emit(const fs::path& folder, const std::string& name, fz::Reader reader, const fs::path& file) {
  const std::vector<char> b = bytes_of(file);
  auto put = [&](const std::string& n, std::size_t size) {
    std::ofstream out(folder / n, std::ios::binary | std::ios::trunc);
    out.put(static_cast<char>(reader));
    out.write(b.data(), static_cast<std::streamsize>(size));
  };
  put(name, b.size());
  for (std::size_t k = 1; k < 8; ++k) put(name + ".cut" + std::to_string(k), b.size() * k / 8);
  put(name + ".cut8", b.size() - 1);
}

/// A partial sweep with rows [0, done) complete.
void partial_sweep(const fs::path& path, std::int64_t done) {
  ex::SweepPartialFile f(path.string(), fz::sweep_layout(), fz::sweep_fingerprint);
  if (done >= 2) f.write(fz::sweep_chunk(0, 2, 2));
  for (std::int64_t i = 2; i < done; ++i) f.write(fz::sweep_chunk(i, 1, i % 2));
  f.close();
}

/// A long-time .partial as a killed run leaves it: rows, a checkpoint at row 6 (if any), more rows.
void long_time_partial(const fs::path& out, bool with_checkpoint) {
  ex::ResultsFile f(out.string(), true, fz::long_time_columns(), fz::long_time_options());
  f.write_parameters({});
  ex::create_resume_record(f, fz::long_time_fingerprint);
  auto append = [&](std::int64_t step) {
    ex::ResultRow r = f.row();
    r.set("step", step);
    r.set("time", 1e-3 * static_cast<double>(step));
    r.set("energy_error", 1e-16);
    r.set("energy_error_window_max", 2e-16);
    f.append(r);
  };
  for (std::int64_t s = 0; s < 6; ++s) append(s * s);
  f.flush();
  if (with_checkpoint) {
    ex::RunCheckpoint c;
    c.rows = f.rows();
    c.loop.step = 30;
    c.loop.t = 0.03;
    c.loop.state.R.setIdentity();
    c.loop.state.Pi = Eigen::Vector3d(1.0, 2.0, 3.0);
    c.loop.memory = {1.0, 0.0, 0.5, 0.25, 0.125};
    c.window_max = {2e-16};
    c.run_max = {3e-16};
    f.write_record("resume", "checkpoint", 0, ex::encode_checkpoint(c, 1));
  }
  for (std::int64_t s = 6; s < 9; ++s) append(s * s);
  f.flush();
  f.abandon({});
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_h5_seeds FOLDER\n");
    return 2;
  }
  const fs::path folder = argv[1];
  fs::create_directories(folder);
  const fs::path work = folder / "work";
  fs::create_directories(work);
  partial_sweep(work / "a.partial", 3);
  emit(folder, "sweep_partial", fz::sweep_resume, work / "a.partial");
  partial_sweep(work / "b.partial", fz::sweep_layout().count);
  emit(folder, "sweep_partial_complete", fz::sweep_resume, work / "b.partial");
  {
    ex::SweepPartialFile f((work / "b.partial").string(), fz::sweep_layout(), fz::sweep_fingerprint, true);
    f.write_final((work / "final.h5").string(), {});
  }
  emit(folder, "sweep_final", fz::sweep_columns, work / "final.h5");
  long_time_partial(work / "lt.h5", true);
  emit(folder, "long_time_partial", fz::long_time_resume, work / "lt.h5.partial");
  long_time_partial(work / "lt0.h5", false);
  emit(folder, "long_time_partial_no_checkpoint", fz::long_time_resume, work / "lt0.h5.partial");
  fs::remove_all(work);
  return 0;
}

// SweepPartialFile (experiments/io/sweep_file.hpp): what `lgi sweep --resume`
// finds in <out>.partial, and the one line each refusal gives. The commands'
// tests (tests/commands/test_sweep.py, test_faults.py) kill real sweeps; the
// file removed between lgi's look at it and its open is a race they cannot
// set up, so it is set up here.
#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <string>

#include "experiments/io/h5md_writer.hpp"  // OutputFileError
#include "experiments/io/sweep_file.hpp"
#include "support/run_command.hpp"

namespace test_sweep_partial_file {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi::experiments;

namespace {
SweepLayout small_layout() {
  SweepLayout layout;
  layout.count = 4;
  layout.error_names = {"energy"};
  return layout;
}

std::string refusal(const std::string& path, const std::string& fingerprint) {
  try {
    SweepPartialFile resumed(path, small_layout(), fingerprint, true);
  } catch (const OutputFileError& e) {
    return e.what();
  }
  return {};
}
}  // namespace

TEST_CASE("a partial sweep resumes with its own fingerprint only", "[sweep][resume]") {
  const std::string path = lgi::testing::scratch_dir("sweep_partial_file") + "/a.h5.partial";
  std::remove(path.c_str());
  {
    SweepPartialFile created(path, small_layout(), "spec A");
    created.close();
  }
  CHECK(refusal(path, "spec A").empty());
  const std::string why = refusal(path, "spec B");
  CHECK(why.find("different spec") != std::string::npos);
  CHECK(why.find("without --resume") != std::string::npos);
}

TEST_CASE("a partial sweep that is not HDF5 yet, or is gone, names the way out", "[sweep][resume]") {
  const std::string dir = lgi::testing::scratch_dir("sweep_partial_file");
  const std::string early = dir + "/early.h5.partial";
  std::ofstream(early, std::ios::binary) << std::string(100, '\0');  // killed while it was being created
  const std::string why_early = refusal(early, "spec A");
  CHECK(why_early.find(early) == 0);
  CHECK(why_early.find("killed before its first write") != std::string::npos);
  CHECK(why_early.find("without --resume") != std::string::npos);

  const std::string gone = dir + "/gone.h5.partial";
  std::remove(gone.c_str());  // removed after `lgi sweep` saw it and before it opened it
  const std::string why_gone = refusal(gone, "spec A");
  CHECK(why_gone.find(gone) == 0);
  CHECK(why_gone.find("removed before it could be opened") != std::string::npos);
  CHECK(why_gone.find("without --resume") != std::string::npos);
}

}  // namespace test_sweep_partial_file

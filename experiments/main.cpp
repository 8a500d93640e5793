// lgi: the command-line front end (README.md, `lgi --help`). All work is in lgi_experiments.
#include <hdf5.h>

#include "experiments/cli/cli.hpp"
#include "experiments/commands/all_commands.hpp"

int main(int argc, char** argv) {
  // HDF5 1.10 leaves a file whose H5Fclose failed (a write refused: disk full, the file-size
  // limit) half closed, and its clean-up at exit then crashes in H5F__close_cb. Every file lgi
  // writes is closed (or abandoned) before run_cli returns, so that clean-up has nothing to do:
  // skip it, and a failed write ends with its one-line error and exit 1 instead of a crash.
  H5dont_atexit();
  // HDF5's automatic error-stack printing off for good: every failure is reported by lgi in one
  // line naming the file (README.md), never as the library's stack of ~100 lines (issue 50).
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  return lgi::experiments::run_cli(argc, argv, lgi::experiments::all_commands());
}

// lgi: the command-line front end (README.md, `lgi --help`). All work is in lgi_experiments.
#include "experiments/cli/cli.hpp"

int main(int argc, char** argv) { return lgi::experiments::run_cli(argc, argv); }

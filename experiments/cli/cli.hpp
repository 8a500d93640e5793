#pragma once
// The `lgi` command (README.md, "Using lgi"): subcommands, exit statuses
// (0 success, 1 the run failed, 2 bad command line or input) and one-line
// errors on stderr.
namespace lgi::experiments {
int run_cli(int argc, char** argv);
}

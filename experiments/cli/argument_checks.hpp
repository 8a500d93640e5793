#pragma once
// Checks of the raw command line that CLI11 does not make (README.md, "Using
// lgi"; issue 50): a value that is empty (`--dt ''`, `--out ''`, `--l=`) or a
// comma-separated list with an empty element (`--schemes rkmk4,,cf4`), or an
// integer past 64 bits (`--save-every 99999999999999999999`, a negative
// unsigned `--seed -1`) is refused naming its flag, where CLI11 would drop it,
// take the default or saturate; and
// a parse error before any subcommand names the unknown word (`lgi
// frobnicate`, `lgi --frob simulate`) instead of "A subcommand is required".
#include <CLI/CLI.hpp>
#include <string>

namespace lgi::experiments {

/// Throws UsageError naming the flag for an empty value of any option of
/// `sub`, or an empty element of a value of an option declared with
/// delimiter(','), or an integer value out of 64-bit range. argv is the whole
/// command line (argv[0] the program).
void check_argument_values(const CLI::App& sub, int argc, const char* const* argv);

/// For a parse error of `app`: the one line naming the unknown subcommand or
/// option that comes before any subcommand; empty if there is none.
std::string unknown_leading_argument(const CLI::App& app, int argc, const char* const* argv);

}  // namespace lgi::experiments

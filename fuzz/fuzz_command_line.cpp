// libFuzzer harness: bytes -> the argv of `lgi` (arguments separated by NUL
// bytes, at most 64) -> CommandLine::parse (experiments/cli/cli.hpp), which
// parses every subcommand's options with CLI11 and checks the arguments that
// need no file, and runs nothing. Every input must end in a status of 0
// (--help, --version: text written), 2 (one line "lgi: ..." naming what is
// wrong) or a subcommand ready to run (nothing written to the error stream).
// Anything else (another status, an exception, exit(), a file read or a run
// started, a crash, a sanitizer report) is a finding.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "experiments/cli/cli.hpp"
#include "experiments/commands/all_commands.hpp"

namespace {

[[noreturn]] void finding(const char* what, const std::string& detail) {
  std::fprintf(stderr, "%s: %s\n", what, detail.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> args{"lgi"};
  std::string current;
  for (std::size_t i = 0; i < size && args.size() < 64; ++i) {
    if (data[i] == 0) {
      args.push_back(current);
      current.clear();
    } else {
      current += static_cast<char>(data[i]);
    }
  }
  if (!current.empty() && args.size() < 64) args.push_back(current);
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  argv.push_back(nullptr);

  lgi::experiments::CommandLine command_line(static_cast<int>(args.size()), argv.data(),
                                            lgi::experiments::all_commands());
  std::ostringstream out, err;
  const std::optional<int> status = command_line.parse(out, err);
  const std::string e = err.str();
  if (!status) {
    if (!e.empty()) finding("a command ready to run wrote an error", e);
  } else if (*status == 2) {
    if (e.rfind("lgi: ", 0) != 0 || e.size() < 7 || e.back() != '\n' || e.find('\n') != e.size() - 1)
      finding("not one error line", e);
  } else if (*status == 0) {
    if (out.str().empty() || !e.empty()) finding("help or version without text", e);
  } else {
    finding("unexpected status", std::to_string(*status));
  }
  return 0;
}

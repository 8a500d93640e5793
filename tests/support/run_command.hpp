#pragma once
// Runs the lgi executable as a user would, capturing exit status, stdout and stderr.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace lgi::testing {

struct CommandResult {
  int status = -1;
  std::string out, err;
};

inline std::string read_text(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

inline std::string scratch_dir(const std::string& name) {
  const std::string dir = std::string(LGI_TEST_TMPDIR) + "/" + name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// Runs `lgi <args>` (args already shell-quoted where needed).
inline CommandResult run_lgi(const std::string& args, const std::string& workdir = LGI_TEST_TMPDIR) {
  static int counter = 0;
  // The process id keeps test programs that CTest runs side by side (-j2) apart.
  const std::string base = workdir + "/cmd" + std::to_string(::getpid()) + "_" + std::to_string(++counter);
  const std::string cmd = std::string(LGI_EXECUTABLE) + " " + args + " > " + base + ".out 2> " + base + ".err";
  const int raw = std::system(cmd.c_str());
  CommandResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = read_text(base + ".out");
  r.err = read_text(base + ".err");
  return r;
}

/// The lines of a command's output or of a text file, without their newlines.
inline std::vector<std::string> split_lines(const std::string& s) {
  std::vector<std::string> lines;
  std::istringstream in(s);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

inline int line_count(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

}  // namespace lgi::testing

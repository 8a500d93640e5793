#pragma once
// The exception for bad input (a scene file, a command-line value): its
// what() is the one-line message printed on stderr, and the command line
// maps it to exit status 2 (README.md). Scene-file messages have the form
//   <file>:<line>: [table] key: what is wrong
// (scene_reader.hpp).
#include <stdexcept>

namespace lgi::experiments {

struct InputError : std::runtime_error {
  using runtime_error::runtime_error;
};

}  // namespace lgi::experiments

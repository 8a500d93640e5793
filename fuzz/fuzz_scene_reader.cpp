// libFuzzer harness: TOML text -> scene (experiments/io/scene_reader.hpp).
// Any input must end in a scene or in InputError with one line; anything
// else (another exception, a crash, a sanitizer report, a message with a
// line break) is a finding.
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <string>

#include "experiments/io/scene_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)lgi::experiments::parse_scene(text, "fuzz.toml");
  } catch (const lgi::experiments::InputError& e) {
    const std::string m = e.what();
    if (m.find('\n') != std::string::npos || m.rfind("fuzz.toml", 0) != 0) {
      std::fprintf(stderr, "bad message: %s\n", m.c_str());
      std::abort();
    }
  }
  return 0;
}

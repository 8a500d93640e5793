// libFuzzer harness: TOML text -> sweep spec (experiments/io/sweep_spec.hpp).
// Any input must end in a spec or in InputError with one line naming the
// file; anything else is a finding.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "experiments/errors/input_error.hpp"
#include "experiments/io/sweep_spec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto spec = lgi::experiments::parse_sweep_spec(text, "fuzz/spec.toml");
    (void)spec.count();
  } catch (const lgi::experiments::InputError& e) {
    const std::string m = e.what();
    if (m.find('\n') != std::string::npos || m.rfind("fuzz/spec.toml", 0) != 0) {
      std::fprintf(stderr, "bad message: %s\n", m.c_str());
      std::abort();
    }
  }
  return 0;
}

#pragma once
// The one-line InputError message that parse_scene throws for a scene text
// (read as "test.toml"); the calling test fails if the text is accepted or
// something else is thrown.
#include <catch2/catch.hpp>

#include <string>

#include "experiments/errors/input_error.hpp"
#include "experiments/io/scene_reader.hpp"

namespace lgi::testing {

inline std::string error_of(const std::string& text) {
  using Catch::Matchers::StartsWith;
  try {
    (void)experiments::parse_scene(text, "test.toml");
  } catch (const experiments::InputError& e) {
    const std::string m = e.what();
    CHECK(m.find('\n') == std::string::npos);  // one line
    CHECK_THAT(m, StartsWith("test.toml"));     // names the file
    return m;
  }
  FAIL("parse_scene accepted bad input:\n" << text);
  return {};
}

}  // namespace lgi::testing

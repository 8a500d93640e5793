#pragma once
// A scene shipped in experiments/scenes/, by name without ".toml", read by
// the same reader as `lgi simulate`.
#include <string>

#include "experiments/io/scene_reader.hpp"

namespace lgi::testing {

inline system::Scene shipped_scene(const std::string& name) {
  return experiments::read_scene(std::string(LGI_SCENES_DIR) + "/" + name + ".toml");
}

}  // namespace lgi::testing

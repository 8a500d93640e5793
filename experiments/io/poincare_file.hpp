#pragma once
// Reads what `lgi periodic --seeds-from-poincare` needs from a file of `lgi
// poincare` (experiments/POINCARE.md "Output"): the level (l, h), the
// section and its axis from /parameters, and the crossings of /events
// (angular_momentum, gamma, direction, index). Anything missing or of the
// wrong shape is an InputError naming the file and the object.
#include <cstdint>
#include <string>
#include <vector>

#include "lie/so3.hpp"

namespace lgi::experiments {

struct PoincareFile {
  double l = 0.0, h = 0.0;
  std::string section;  // richter, gamma, gamma1, gamma2 or gamma3
  lie::Vec3 axis = lie::Vec3::UnitZ();
  std::vector<lie::Vec3> angular_momentum, gamma;  // one per /events row
  std::vector<std::int64_t> direction, orbit;      // /events direction and index
};

PoincareFile read_poincare_file(const std::string& path);

}  // namespace lgi::experiments

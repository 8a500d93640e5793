#pragma once
// Reads what `lgi periodic --seeds-from-poincare` needs from a file of `lgi
// poincare` (experiments/POINCARE.md "Output"): the level (l, h), the
// section and its axis from /parameters, and the crossings of /events
// (angular_momentum, gamma, direction, index). A Cardan top's file
// (/parameters system "cardan (T^3)", docs/cardan.md §9.2) has no axis; its
// crossings are read as cardan_angles, cardan_momenta and piece, and its
// scene_toml is kept (lgi periodic checks it is the same top). Anything
// missing or of the wrong shape is an InputError naming the file and the object.
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
  bool cardan = false;                             // a Cardan top's section S = -sin q2 dq2/dt (then:)
  std::string scene_toml;                          // /parameters scene_toml
  std::vector<lie::Vec3> cardan_angles, cardan_momenta;  // /events q and p
  std::vector<std::int64_t> piece;                 // /events piece (±1, 2, 3)
};

PoincareFile read_poincare_file(const std::string& path);

}  // namespace lgi::experiments

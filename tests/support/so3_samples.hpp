#pragma once
// The deterministic samples ξ = θ n on which the so(3) property tests check
// every property: θ from kAngles (the series/closed-form switches of
// lie/so3.hpp sit at 1e-4 and 1e-2, and the log is most delicate next to π),
// n from axes() (the coordinate axes and a few generic unit axes, one of them
// close to a coordinate axis); plus test vectors not parallel to any axis and
// the max-entry error measure.
#include <array>
#include <cstddef>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "lie/so3.hpp"

namespace lgi::testing {

inline const std::array<double, 10> kAngles = {0.0,  1e-12, 1e-8, 1e-4, 1e-2, 1.0, 2.0, std::numbers::pi - 1e-6,
                                               std::numbers::pi - 1e-8, std::numbers::pi};

inline std::vector<lie::Vec3> axes() {
  using lie::Vec3;
  return {Vec3::UnitX(),
          Vec3::UnitY(),
          Vec3::UnitZ(),
          Vec3(1.0, 2.0, 3.0).normalized(),
          Vec3(-0.7, 0.2, 0.5).normalized(),
          Vec3(1e-3, -1.0, 2e-3).normalized()};  // close to −e2: near-ties in Shepperd
}

struct Sample {
  double theta;  // nominal angle
  int axis;      // index into axes()
  lie::Vec3 xi;  // θ n as stored (|ξ| may differ from θ in the last bit)
};

inline std::vector<Sample> samples() {
  std::vector<Sample> out;
  const std::vector<lie::Vec3> ax = axes();
  for (double th : kAngles) {
    for (std::size_t k = 0; k < ax.size(); ++k) out.push_back({th, static_cast<int>(k), th * ax[k]});
  }
  return out;
}

inline std::string describe(const Sample& s) {
  std::ostringstream o;
  o.precision(17);
  o << "theta = " << s.theta << ", axis #" << s.axis << ", xi = (" << s.xi.x() << ", " << s.xi.y() << ", "
    << s.xi.z() << ")";
  return o.str();
}

// Test vectors (η, ω, …) that are not parallel to any axis above.
inline const lie::Vec3 kEta(0.3, -0.5, 0.8);
inline const lie::Vec3 kEta2(-1.1, 0.4, 0.25);

// Error measures: the largest entry in absolute value.
inline double maxabs(const lie::Mat3& m) { return m.cwiseAbs().maxCoeff(); }
inline double maxabs(const lie::Vec3& v) { return v.cwiseAbs().maxCoeff(); }

}  // namespace lgi::testing

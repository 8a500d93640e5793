#pragma once
// A scene as read from its TOML file (experiments/scene_reader.hpp): the
// body, the torque terms it declares, the initial state and the run
// defaults. Plain data; the model is assembled from it by make_model().
#include <optional>
#include <string>

#include "integrators/system/inertia.hpp"
#include "lie/product_state.hpp"

namespace lgi::system {

struct GravitySpec {
  double g = 9.81;
};
struct SpringSpec {
  double stiffness = 0.0;
  double damping = 0.0;
  Mat3 rest = Mat3::Identity();
};
struct DriveSpec {
  Vec3 torque_amplitude = Vec3::Zero();
  double angular_frequency = 0.0;
  double phase = 0.0;
};

struct Scene {
  std::string name;
  std::string description;
  std::string file;       // path as given
  std::string toml_text;  // the full file, for provenance

  Mat3 inertia = Mat3::Identity();  // J about the reference point, symmetric positive definite
  std::optional<double> mass;
  std::optional<Vec3> center_of_mass;  // χ, body coordinates from the fixed point
  bool allow_unphysical = false;

  std::optional<GravitySpec> gravity;
  std::optional<SpringSpec> spring;
  std::optional<DriveSpec> drive;

  lie::SO3xR3 initial;  // (R0, Π0)

  // [run]: defaults for the command line, which overrides each of them.
  std::optional<double> t_end;
  std::optional<double> dt;
  std::optional<double> tol;

  bool is_free_body() const { return !gravity && !spring && !drive; }
};

}  // namespace lgi::system

// The keys of each torque term's scene table (experiments/scenes/README.md).
#include "experiments/io/scene_term_tables.hpp"

namespace lgi::experiments::scene_toml {

using system::Scene;

template <>
system::GravityTerm::Parameters read_term_table<system::GravityTerm>(const Table& gravity, const Scene& s) {
  constexpr std::array<std::string_view, 1> keys = {"g"};
  gravity.check_keys(keys);
  system::GravityTerm::Parameters p;
  if (const auto g = gravity.optional_number("g")) {
    if (!(*g >= 0.0)) {
      gravity.fail(*gravity.get("g"), "g", "must be >= 0 (a magnitude; gravity points along -e3), got " + fmt(*g));
    }
    p.g = *g;
  }
  if (!s.mass) gravity.rd.fail(gravity.line, "body", "mass", "missing: [gravity] needs the body's mass");
  if (!s.center_of_mass) {
    gravity.rd.fail(gravity.line, "body", "center_of_mass", "missing: [gravity] needs the body's centre of mass");
  }
  return p;
}

template <>
system::SpringTerm::Parameters read_term_table<system::SpringTerm>(const Table& spring, const Scene& /*s*/) {
  constexpr std::array<std::string_view, 3> keys = {"stiffness", "damping", "rest_quaternion"};
  spring.check_keys(keys);
  system::SpringTerm::Parameters p;
  p.stiffness = spring.required_number("stiffness", "k in N m/rad");
  if (!(p.stiffness >= 0.0)) spring.fail(*spring.get("stiffness"), "stiffness", "must be >= 0, got " + fmt(p.stiffness));
  p.damping = spring.required_number("damping", "c in N m s/rad");
  if (!(p.damping >= 0.0)) spring.fail(*spring.get("damping"), "damping", "must be >= 0, got " + fmt(p.damping));
  if (const toml::node* n = spring.get("rest_quaternion")) p.rest = unit_quaternion(spring, "rest_quaternion", *n);
  return p;
}

template <>
system::HarmonicDriveTerm::Parameters read_term_table<system::HarmonicDriveTerm>(const Table& drive,
                                                                               const Scene& /*s*/) {
  constexpr std::array<std::string_view, 3> keys = {"torque_amplitude", "angular_frequency", "phase"};
  drive.check_keys(keys);
  system::HarmonicDriveTerm::Parameters p;
  const toml::node* a = drive.get("torque_amplitude");
  if (!a) drive.fail_here("torque_amplitude", "missing (required: the body torque amplitude A in N m)");
  p.torque_amplitude = drive.vec3("torque_amplitude", *a);
  p.angular_frequency = drive.required_number("angular_frequency", "omega in rad/s");
  p.phase = drive.optional_number("phase").value_or(0.0);
  return p;
}

template <>
system::MagneticDipoleTerm::Parameters read_term_table<system::MagneticDipoleTerm>(const Table& magnetic,
                                                                                 const Scene& /*s*/) {
  constexpr std::array<std::string_view, 2> keys = {"dipole_moment", "field"};
  magnetic.check_keys(keys);
  system::MagneticDipoleTerm::Parameters p;
  const toml::node* mu = magnetic.get("dipole_moment");
  if (!mu) magnetic.fail_here("dipole_moment", "missing (required: the body's dipole moment mu in A m^2, body frame)");
  p.dipole_moment = magnetic.vec3("dipole_moment", *mu);
  const toml::node* b = magnetic.get("field");
  if (!b) magnetic.fail_here("field", "missing (required: the uniform field B in T, space frame)");
  p.field = magnetic.vec3("field", *b);
  return p;
}

}  // namespace lgi::experiments::scene_toml

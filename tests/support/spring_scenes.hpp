#pragma once
// Scenes of a torsional spring on the body of inertia (1, 2, 2.5), started
// away from its rest attitude, for the tests of the torque schemes: the bare
// undamped spring (the discrete-gradient case), with damping and a drive, and
// with gravity added too. Each is the same text a scene file would hold.
#include <string>

namespace lgi::testing {

// `body_extra` joins [body]; `tables` go between [spring] and [initial].
inline std::string spring_scene(const std::string& name, double damping, const std::string& body_extra = "",
                                 const std::string& tables = "") {
  return "name = \"" + name + "\"\n[body]\ninertia = [1.0, 2.0, 2.5]\n" + body_extra +
         "[spring]\nstiffness = 10.0\ndamping = " + std::to_string(damping) + "\n" + tables +
         "[initial]\nrotation_vector = [1.0, 0.5, -0.3]\nangular_velocity = [0.4, -1.0, 2.0]\n"
         "[run]\nt_end = 10.0\n";
}

inline const std::string drive_table =
    "[drive]\ntorque_amplitude = [0.3, -0.2, 0.1]\nangular_frequency = 2.0\nphase = 0.3\n";

inline const std::string undamped_spring_toml = spring_scene("undamped spring", 0.0);
inline const std::string damped_driven_toml = spring_scene("damped spring with a drive", 5.0, "", drive_table);
// Gravity, a damped spring and a drive at once.
inline const std::string kitchen_sink_toml =
    spring_scene("everything", 0.5, "mass = 2.0\ncenter_of_mass = [0.1, 0.2, 0.3]\n", "[gravity]\ng = 9.81\n" + drive_table);

}  // namespace lgi::testing

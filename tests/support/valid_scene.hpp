#pragma once
// A valid scene text (a heavy top with every table) for the scene-reader
// tests to read as is or to break one line of.
#include <string>

namespace lgi::testing {

// A valid scene used as the base for several bad-input tests; line numbers:
//  1 name, 2 [body], 3 mass, 4 inertia, 5 center_of_mass, 6 [gravity],
//  7 g, 8 [initial], 9 euler_zxz, 10 euler_zxz_rates, 11 [run], 12 t_end,
//  13 dt.
inline const std::string valid_top = R"(name = "top"
[body]
mass = 5
inertia = [5.8, 5.8, 1]
center_of_mass = [0, 0, 1]
[gravity]
g = 9.81
[initial]
euler_zxz = [0, 0.3490658503988659, 0]
euler_zxz_rates = [0, 0, 50]
[run]
t_end = 10
dt = 1e-3
)";

}  // namespace lgi::testing

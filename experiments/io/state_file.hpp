#pragma once
// Reading a table of initial states (the --state-file of lgi indicators,
// experiments/INDICATORS.md): one state per row, given by its angular
// momentum Π (body frame) and its vertical Γ = Rᵀe3 (body frame).
//   - HDF5: a group with the datasets angular_momentum (n×3) and gamma (n×3),
//     such as /equilibria of an `lgi equilibria` file. If several groups
//     have both, /equilibria is taken; otherwise the file is refused.
//   - CSV: a header line naming the columns angular_momentum_1..3 and
//     gamma_1..3 (others are ignored), as lgi writes its tables beside the
//     HDF5 file; then one row of numbers per state.
// Every problem throws InputError with one line naming the file (and the row).
#include <string>
#include <vector>

#include "integrators/system/cardan.hpp"
#include "integrators/system/rigid_body.hpp"
#include "lie/so3.hpp"

namespace lgi::experiments {

struct StateRows {
  std::vector<lie::Vec3> angular_momentum, gamma;
  std::string source;  // "/equilibria" (the HDF5 group) or "CSV"
};

/// Reads the states of `path` (HDF5 if the file is HDF5, CSV otherwise).
StateRows read_state_file(const std::string& path);

/// The states of the rows: R from Γ with the rotation about the vertical fixed
/// (gamma_attitude.hpp), Π as given. A zero Γ throws InputError naming `where`
/// and the row (0 first); any other is normalised, and `normalised` counts the
/// rows whose |Γ| differed from 1 by more than 1e-12.
std::vector<system::State> states_of(const StateRows& rows, const std::string& where, int& normalised);

/// States of a Cardan top (T³ × ℝ³): an HDF5 file with one group holding the n×3 datasets
/// cardan_angles and cardan_momenta (`lgi indicators` on a Cardan scene) or initial_cardan_angles
/// and initial_cardan_momenta (`lgi chaos-map`'s /orbits). Throws InputError naming the file:
/// no such group, several, rows that differ in count, no rows, a value that is not finite.
std::vector<system::TorusState> read_cardan_state_file(const std::string& path);

}  // namespace lgi::experiments

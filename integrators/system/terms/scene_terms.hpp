#pragma once
// The one list of torque terms a scene file can declare. The scene's
// parameters (system/scene.hpp), the scene model and the run-time dispatch
// (system/model.hpp) are all generated from it. Adding a term: write its file
// in this folder, add it here, and read its table in the scene reader
// (README, "Adding a potential").
#include <optional>
#include <tuple>

#include "integrators/system/terms/gravity.hpp"
#include "integrators/system/terms/harmonic_drive.hpp"
#include "integrators/system/terms/magnetic_dipole.hpp"
#include "integrators/system/terms/spring.hpp"

namespace lgi::system {

template <class... Terms>
struct TermList {
  /// Each term's scene parameters, present where the scene declares its table.
  using Parameters = std::tuple<std::optional<typename Terms::Parameters>...>;
  template <template <class...> class Model, template <class> class Wrap>
  using apply = Model<Wrap<Terms>...>;
};

using SceneTerms = TermList<GravityTerm, SpringTerm, HarmonicDriveTerm, MagneticDipoleTerm>;

}  // namespace lgi::system

#pragma once
// A scene as read from its TOML file (experiments/io/scene_reader.hpp): the
// body, the parameters of the torque terms it declares (one slot per term of
// SceneTerms, terms/scene_terms.hpp), the initial state and the run defaults.
// Plain data; the model is assembled from it by make_model().
#include <optional>
#include <string>

#include "integrators/system/cardan.hpp"
#include "integrators/system/inertia.hpp"
#include "integrators/system/terms/scene_terms.hpp"
#include "lie/product_state.hpp"

namespace lgi::system {

struct Scene {
  std::string name;
  std::string description;
  std::string file;       // path as given
  std::string toml_text;  // the full file, for provenance

  Mat3 inertia = Mat3::Identity();  // J about the reference point, symmetric positive definite
  std::optional<double> mass;
  std::optional<Vec3> center_of_mass;  // χ, body coordinates from the fixed point
  bool allow_unphysical = false;

  SceneTerms::Parameters terms;  // std::optional<T::Parameters> per scene term

  lie::SO3xR3 initial;  // (R0, Π0)

  /// [suspension]: the body hangs in a Cardan frame (docs/cardan.md); its
  /// state lives on T³ × ℝ³, from [initial] cardan_angles and cardan_rates,
  /// and `initial` holds the body's (R, Π) at that state.
  std::optional<SuspensionParameters> suspension;
  TorusState cardan_initial{};

  // [run]: defaults for the command line, which overrides each of them.
  std::optional<double> t_end;
  std::optional<double> dt;
  std::optional<double> tol;

  /// The parameters of term T, empty where the scene does not declare it.
  template <class T>
  std::optional<typename T::Parameters>& declared() {
    return std::get<std::optional<typename T::Parameters>>(terms);
  }
  template <class T>
  const std::optional<typename T::Parameters>& declared() const {
    return std::get<std::optional<typename T::Parameters>>(terms);
  }
  /// How many torque terms the scene declares.
  int declared_terms() const {
    return std::apply([](const auto&... p) { return (int{p.has_value()} + ... + 0); }, terms);
  }
  bool is_free_body() const { return declared_terms() == 0; }
  /// Whether T is the one torque term the scene declares.
  template <class T>
  bool declares_only() const {
    return declared<T>().has_value() && declared_terms() == 1;
  }
  BodyProperties body() const { return {inertia, mass.value_or(0.0), center_of_mass.value_or(Vec3::Zero())}; }
};

}  // namespace lgi::system

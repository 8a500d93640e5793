#pragma once
// The scheme registry: every name a user can pass to --scheme, with its
// order, family, properties, reference, and a function that runs it on any
// scene's model. `lgi schemes` and the generic tests read this table.
// Adding a scheme: write its header, then add one line to registry.cpp.
#include <string>
#include <string_view>
#include <vector>

#include "integrators/stepper_loop.hpp"
#include "integrators/system/model.hpp"

namespace lgi::integrators {

struct SchemeProperties {
  bool symplectic = false;
  bool symmetric = false;                    // Φ₋ₕ ∘ Φₕ = id (tested to round-off)
  bool conserves_energy = false;             // exactly, to round-off
  bool conserves_momentum_norm = false;      // |Π| for a free body
  bool conserves_spatial_momentum = false;   // m = RΠ for a free body
  bool conserves_vertical_momentum = false;  // Π·Γ for a heavy top
  bool implicit = false;
  bool adaptive = false;
  bool baseline = false;                     // a Boost.Odeint baseline in coordinates, not a Lie-group scheme
  bool euler_angle_chart = false;            // integrates Euler ZXZ angles: /particles/body/euler_zxz is written
};

/// Which scenes a scheme can run on; others are refused with exit 1.
enum class SceneSupport {
  any,
  free_body_only,     // needs the free body (the exact flow, DMV without splitting)
  conservative_only,  // torques from a potential only: no damping, no drive
};

/// Runs a scheme on a scene's model from the given state. Dispatches on the
/// model once; the step loop inside is compiled for that model.
using RunFunction = RunStats (*)(const system::AnyModel& model, State& state, const RunConfig& cfg,
                                 Observer& observer);

struct SchemeInfo {
  std::string name;
  int order = 0;              // 0: not applicable (exact)
  std::string family;
  SchemeProperties properties;
  SceneSupport support = SceneSupport::any;
  std::string reference;
  std::string notes;
  RunFunction run = nullptr;
  int order_with_torque = 0;  // order on scenes with torques where it differs (Strang splitting); 0: the same
  std::string base_scheme{};  // a composition's base scheme (`lgi schemes --json` "base"); empty otherwise
};

const std::vector<SchemeInfo>& scheme_registry();

/// Registration, one function per family, each in its own registry_<family>.cpp.
void add_lie_group_runge_kutta_schemes(std::vector<SchemeInfo>& registry);
void add_variational_schemes(std::vector<SchemeInfo>& registry);        // dmv, lgvi, dmv-pre*
void add_energy_momentum_schemes(std::vector<SchemeInfo>& registry);    // simo-wong
void add_splitting_schemes(std::vector<SchemeInfo>& registry);          // split-exact
void add_implicit_schemes(std::vector<SchemeInfo>& registry);           // rkmk-gauss*, L-stable scheme
void add_baseline_schemes(std::vector<SchemeInfo>& registry);           // COORDS/STEPPER (Boost.Odeint)
/// nullptr if no scheme has that name.
const SchemeInfo* find_scheme(std::string_view name);
/// Empty if the scheme can run on the model, else the reason it cannot.
std::string unsupported_reason(const SchemeInfo& scheme, const system::AnyModel& model);

}  // namespace lgi::integrators

#pragma once
// The scheme registry: every name a user can pass to --scheme, with its
// order, family, properties, reference, and a function that runs it on any
// scene's model. `lgi schemes` and the generic tests read this table.
// Adding a scheme: write its header, then add one line to registry.cpp.
#include <string>
#include <string_view>
#include <vector>

#include "integrators/ensemble/lane_mode.hpp"
#include "integrators/core/scheme_facts.hpp"
#include "integrators/core/stepper_loop.hpp"
#include "integrators/system/model.hpp"

namespace lgi::system {
struct CardanTop;
}  // namespace lgi::system

namespace lgi::integrators {

/// Runs a scheme on a scene's model from the given state. Dispatches on the
/// model once; the step loop inside is compiled for that model.
using RunFunction = RunStats (*)(const system::AnyModel& model, State& state, const RunConfig& cfg,
                                 Observer& observer);

/// Runs a scheme of T³ × ℝ³ on a Cardan top (integrators/registry/torus_registry.hpp).
using CardanRunFunction = RunStats (*)(const system::CardanTop& model, system::TorusState& state,
                                       const TorusRunConfig& cfg, TorusObserver& observer);

/// One scheme, on either state space: `run` for SO(3) × ℝ³, or (support
/// cardan_only) `run_cardan` for T³ × ℝ³; the other is null.
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
  // driven by the stepper loop, which honours RunConfig::events (not the baselines, nor the processed
  // compositions: processed_composition.hpp)
  bool locates_events = true;
  /// A run can be resumed from a checkpoint (RunConfig::checkpoints; scheme_interface.hpp, "Resume").
  bool resumable = false;
  CardanRunFunction run_cardan = nullptr;
  /// The fixed-step loop on the scheme's step(): for an adaptive scheme, its
  /// propagated solution on a fixed grid (order checks); otherwise run_cardan.
  CardanRunFunction run_cardan_fixed = nullptr;
  /// The SIMD lane kernel the scheme's facts declare (SchemeFacts::lane_kernel) and what the
  /// ensemble runs it with; kernel none: one trajectory at a time (docs/ensemble.md).
  LaneMode lanes{};
};

const std::vector<SchemeInfo>& scheme_registry();

/// Adds a scheme defined outside lgi (docs/extending.md, register_scheme.hpp
/// for a scheme type that carries its facts): from then on find_scheme(),
/// scheme_registry() and everything built on them (the simulate driver,
/// the verification kit) see it. Throws std::invalid_argument for an empty
/// or taken name or a null run function. Register before looking schemes up:
/// the first 64 registrations keep earlier SchemeInfo pointers valid, later
/// ones may move the table. Not safe against concurrent lookups.
void register_scheme(SchemeInfo scheme);

/// Registration, one function per family, each in its own registry_<family>.cpp.
void add_lie_group_runge_kutta_schemes(std::vector<SchemeInfo>& registry);
void add_verner_high_order_pairs(std::vector<SchemeInfo>& registry);  // rkmk-verner87, rkmk-verner98
void add_cayley_pairs(std::vector<SchemeInfo>& registry);             // rkmk-cayley-dp54 … rkmk-cayley-verner98
void add_variational_schemes(std::vector<SchemeInfo>& registry);        // dmv, lgvi, dmv-pre*
void add_energy_momentum_schemes(std::vector<SchemeInfo>& registry);    // simo-wong
void add_splitting_schemes(std::vector<SchemeInfo>& registry);          // split-exact
void add_implicit_schemes(std::vector<SchemeInfo>& registry);           // rkmk-gauss*, L-stable scheme
void add_baseline_schemes(std::vector<SchemeInfo>& registry);           // COORDS/STEPPER (Boost.Odeint)
/// nullptr if no scheme has that name.
const SchemeInfo* find_scheme(std::string_view name);
/// The schemes of T³ × ℝ³ (the Cardan top; registry_cardan.cpp): records of
/// the same kind, with support cardan_only and run_cardan set.
const std::vector<SchemeInfo>& cardan_scheme_registry();
/// nullptr if no scheme of T³ × ℝ³ has that name.
const SchemeInfo* find_cardan_scheme(std::string_view name);
/// The state space a scheme runs on: "SO(3) x R^3" or "T^3 x R^3".
const char* state_space_name(const SchemeInfo& scheme);
/// Empty if the scheme can run on the model, else the reason it cannot.
std::string unsupported_reason(const SchemeInfo& scheme, const system::AnyModel& model);
/// Empty if a scheme with this support can run on the model, else what it
/// needs ("needs a free body (...)").
std::string support_refusal(SceneSupport support, const system::AnyModel& model);

}  // namespace lgi::integrators

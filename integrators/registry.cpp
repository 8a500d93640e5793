#include "integrators/registry.hpp"

#include <variant>

#include "integrators/commutator_free.hpp"
#include "integrators/crouch_grossman.hpp"
#include "integrators/exact_free_flow.hpp"
#include "integrators/rkmk.hpp"
#include "integrators/rkmk_adaptive.hpp"

namespace lgi::integrators {
namespace {

template <class Scheme>
RunStats run_fixed(const system::AnyModel& model, State& state, const RunConfig& cfg, Observer& observer) {
  return std::visit(
      [&](const auto& m) {
        Scheme scheme;
        return integrate_fixed(scheme, m, state, cfg, observer);
      },
      model);
}

RunStats run_exact(const system::AnyModel& model, State& state, const RunConfig& cfg, Observer& observer) {
  ExactFreeFlow scheme;
  return integrate_fixed(scheme, std::get<system::FreeBody>(model), state, cfg, observer);
}

RunStats run_rkmk_dp54(const system::AnyModel& model, State& state, const RunConfig& cfg, Observer& observer) {
  return std::visit(
      [&](const auto& m) {
        RkmkDp54 scheme(cfg.tol);
        return integrate_adaptive(scheme, m, state, cfg, observer);
      },
      model);
}

constexpr SchemeProperties explicit_lie_group{};

std::vector<SchemeInfo> build_registry() {
  const char* munthe_kaas = "Munthe-Kaas, Appl. Numer. Math. 29 (1999) 115-127; Iserles et al., Acta Numerica 9 (2000) 5.3";
  std::vector<SchemeInfo> r;
  // name, order, family, properties, support, reference, notes, run
  r.push_back({"exact", 0, "exact flow", {false, true, true, true, true, false, false}, SceneSupport::free_body_only,
               "Jacobi elliptic functions for Pi; elliptic integral of the third kind for R (Celledoni, Fasso, "
               "Safstrom & Zanna, SIAM J. Sci. Comput. 30 (2008))",
               "free bodies only; evaluated from the initial state at every output time", &run_exact});
  r.push_back({"lie-euler", 1, "RKMK", explicit_lie_group, SceneSupport::any,
               std::string(munthe_kaas) + "; tableau: explicit Euler", "", &run_fixed<LieEuler>});
  r.push_back({"rkmk2", 2, "RKMK", explicit_lie_group, SceneSupport::any,
               std::string(munthe_kaas) + "; tableau: Heun (HNW I, Table 1.1)", "", &run_fixed<Rkmk2>});
  r.push_back({"rkmk3", 3, "RKMK", explicit_lie_group, SceneSupport::any,
               std::string(munthe_kaas) + "; tableau: Kutta's third order (HNW I, Table 1.1)", "",
               &run_fixed<Rkmk3>});
  r.push_back({"rkmk4", 4, "RKMK", explicit_lie_group, SceneSupport::any,
               std::string(munthe_kaas) + "; tableau: classical RK4 (HNW I, Table 1.2)", "", &run_fixed<Rkmk4>});
  r.push_back({"rkmk-dp54", 5, "RKMK", {false, false, false, false, false, false, true}, SceneSupport::any,
               std::string(munthe_kaas) + "; tableau: Dormand & Prince, J. Comput. Appl. Math. 6 (1980)",
               "adaptive (--tol); error estimated on the algebra and in Pi", &run_rkmk_dp54});
  r.push_back({"cg3", 3, "Crouch-Grossman", explicit_lie_group, SceneSupport::any,
               "Crouch & Grossman, J. Nonlinear Sci. 3 (1993); Owren & Marthinsen, BIT 39 (1999)", "",
               &run_fixed<Cg3>});
  r.push_back({"cg4a", 4, "Crouch-Grossman", explicit_lie_group, SceneSupport::any,
               "Jackiewicz, Marthinsen & Owren, Adv. Comput. Math. 13 (2000), App. A Ex. 1", "5 stages",
               &run_fixed<Cg4a>});
  r.push_back({"cf4", 4, "commutator-free", explicit_lie_group, SceneSupport::any,
               "Celledoni, Marthinsen & Owren, Future Gener. Comput. Syst. 19 (2003)", "two exponentials per step",
               &run_fixed<Cf4>});
  return r;
}

}  // namespace

const std::vector<SchemeInfo>& scheme_registry() {
  static const std::vector<SchemeInfo> registry = build_registry();
  return registry;
}

const SchemeInfo* find_scheme(std::string_view name) {
  for (const auto& s : scheme_registry())
    if (s.name == name) return &s;
  return nullptr;
}

std::string unsupported_reason(const SchemeInfo& scheme, const system::AnyModel& model) {
  if (scheme.support == SceneSupport::free_body_only && !std::holds_alternative<system::FreeBody>(model))
    return "scheme '" + scheme.name + "' needs a free body (no [gravity], [spring] or [drive])";
  return {};
}

}  // namespace lgi::integrators

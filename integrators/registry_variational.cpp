// Registry lines for: dmv, lgvi, dmv-pre4..10 (structure-preserving schemes, docs/math.md §5).
#include "integrators/moser_veselov.hpp"
#include "integrators/registry_support.hpp"

namespace lgi::integrators {
namespace {

/// Runs Scheme after refusing, here too, a scene outside `Support`: a caller
/// that skipped unsupported_reason() gets a failed run with the reason, not
/// a trajectory that silently ignores a drive or a damper.
template <class Scheme, const char* Name, SceneSupport Support>
RunStats run_variational(const system::AnyModel& model, State& state, const RunConfig& cfg, Observer& observer) {
  SchemeInfo self;
  self.name = Name;
  self.support = Support;
  if (std::string why = unsupported_reason(self, model); !why.empty()) {
    RunStats refused;
    refused.ok = false;
    refused.status = std::move(why);
    return refused;
  }
  return run_fixed<Scheme>(model, state, cfg, observer);
}

constexpr char dmv_name[] = "dmv";
constexpr char lgvi_name[] = "lgvi";
constexpr char pre4_name[] = "dmv-pre4";
constexpr char pre6_name[] = "dmv-pre6";
constexpr char pre8_name[] = "dmv-pre8";
constexpr char pre10_name[] = "dmv-pre10";

}  // namespace

void add_variational_schemes(std::vector<SchemeInfo>& r) {
  const std::string lee_leok =
      "Lee, Leok & McClamroch, IEEE CCA (2005) and CMAME 196 (2007); Moser & Veselov, Commun. Math. Phys. 139 "
      "(1991)";
  const std::string hairer_vilmart =
      "Hairer & Vilmart, J. Phys. A 39 (2006) 13225-13235, Algorithm 2.2; modified inertia: Table 1 and the "
      "authors' DMV10.f";
  const std::string newton = "Newton on the Cayley parameter (analytic Jacobian, <= 50 iterations)";
  r.push_back({"dmv", 2, "Moser-Veselov",
               {.symplectic = true, .symmetric = true, .conserves_energy = true, .conserves_momentum_norm = true,
                .conserves_spatial_momentum = true, .implicit = true},
               SceneSupport::free_body_only, lee_leok,
               "discrete Moser-Veselov: free bodies only (lgvi adds a potential); " + newton,
               &run_variational<Dmv, dmv_name, SceneSupport::free_body_only>});
  add_compositions<Dmv>(r, r.back());
  r.push_back({"lgvi", 2, "Moser-Veselov",
               {.symplectic = true, .symmetric = true, .conserves_momentum_norm = true,
                .conserves_spatial_momentum = true, .conserves_vertical_momentum = true, .implicit = true},
               SceneSupport::conservative_only, lee_leok,
               "kick(h/2) o DMV(h) o kick(h/2) with the potential torque; equals dmv on a free body (and then "
               "conserves its energy too); " + newton,
               &run_variational<Lgvi, lgvi_name, SceneSupport::conservative_only>});
  add_compositions<Lgvi>(r, r.back());
  // Not symplectic for order > 2 (Hairer-Vilmart Table 2, Sect. 4.3): a Poisson integrator for Pi.
  constexpr SchemeProperties preprocessed{.symmetric = true, .conserves_momentum_norm = true,
                                          .conserves_spatial_momentum = true,
                                          .conserves_vertical_momentum = true, .implicit = true};
  const std::string pre_notes =
      "free body: DMV with modified moments of inertia, series in h^2 in H and |Pi|^2 (conserves H, |Pi|, "
      "R Pi; Poisson for Pi, not symplectic); with a potential: Strang splitting kick(h/2) o preDMV(h) o "
      "kick(h/2), order 2 (Pi.Gamma still conserved); ";
  r.push_back({"dmv-pre4", 4, "Moser-Veselov", preprocessed, SceneSupport::conservative_only, hairer_vilmart,
               pre_notes + newton, &run_variational<DmvPre4, pre4_name, SceneSupport::conservative_only>,
               /*order_with_torque=*/2});
  r.push_back({"dmv-pre6", 6, "Moser-Veselov", preprocessed, SceneSupport::conservative_only, hairer_vilmart,
               pre_notes + newton, &run_variational<DmvPre6, pre6_name, SceneSupport::conservative_only>,
               /*order_with_torque=*/2});
  r.push_back({"dmv-pre8", 8, "Moser-Veselov", preprocessed, SceneSupport::conservative_only, hairer_vilmart,
               pre_notes + newton, &run_variational<DmvPre8, pre8_name, SceneSupport::conservative_only>,
               /*order_with_torque=*/2});
  r.push_back({"dmv-pre10", 10, "Moser-Veselov", preprocessed, SceneSupport::conservative_only,
               hairer_vilmart + " (s9, d9 from DMV10.f only)", pre_notes + newton,
               &run_variational<DmvPre10, pre10_name, SceneSupport::conservative_only>,
               /*order_with_torque=*/2});
}

}  // namespace lgi::integrators

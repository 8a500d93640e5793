// Registry lines for: dmv, lgvi, dmv-pre4..10 (structure-preserving schemes, docs/math.md §5).
#include "integrators/schemes/moser_veselov_preprocessed.hpp"
#include "integrators/registry/registry_support.hpp"

namespace lgi::integrators {

void add_variational_schemes(std::vector<SchemeInfo>& r) {
  const std::string newton = "Newton on the Cayley parameter (analytic Jacobian, <= 50 iterations)";
  add_scheme<Dmv>(r, {.name = "dmv",
                      .family = "Moser-Veselov",
                      .notes = "discrete Moser-Veselov: free bodies only (lgvi adds a potential); " + newton});
  add_compositions<Dmv>(r, r.back());
  add_scheme<Lgvi>(r, {.name = "lgvi",
                       .family = "Moser-Veselov",
                       .notes = "kick(h/2) o DMV(h) o kick(h/2) with the potential torque; equals dmv on a free body "
                                "(and then conserves its energy too); " + newton});
  add_compositions_and_processed<Lgvi>(r);
  const std::string pre_notes =
      "free body: DMV with modified moments of inertia, series in h^2 in H and |Pi|^2 (conserves H, |Pi|, "
      "R Pi; Poisson for Pi, not symplectic); with a potential: Strang splitting kick(h/2) o preDMV(h) o "
      "kick(h/2), order 2 (Pi.Gamma still conserved); " + newton;
  add_scheme<DmvPre4>(r, {.name = "dmv-pre4", .family = "Moser-Veselov", .notes = pre_notes});
  add_scheme<DmvPre6>(r, {.name = "dmv-pre6", .family = "Moser-Veselov", .notes = pre_notes});
  add_scheme<DmvPre8>(r, {.name = "dmv-pre8", .family = "Moser-Veselov", .notes = pre_notes});
  add_scheme<DmvPre10>(r, {.name = "dmv-pre10", .family = "Moser-Veselov", .notes = pre_notes});
  r.back().reference += " (s9, d9 from DMV10.f only)";
}

}  // namespace lgi::integrators

#include "experiments/commands/periodic/periodic_tables.hpp"

#include <cmath>

#include "experiments/commands/periodic/critical_seeds.hpp"

namespace lgi::experiments {

std::vector<TableColumn> periodic_columns(const HeavyTopBody& body, const std::vector<FamilyOrbit>& rows,
                                          const std::optional<PhaseSection>& section) {
  std::vector<TableColumn> c = {{"family", 1, true}, {"index", 1, true}, {"l"}, {"h"}, {"period"},
                                {"angular_momentum", 3}, {"gamma", 3}, {"residual"}, {"multipliers", 12},
                                {"stability", 1, false, {}, {}, {}, true}, {"event", 1, false, {}, {}, {}, true},
                                {"degenerate", 1, true}, {"equilibrium", 1, true}, {"omega"},
                                {"trivial_deviation"}, {"product_deviation"}, {"parent", 1, true},
                                {"reduced_trace"}, {"invariance_defect"},
                                {"family_end", 1, false, {}, {}, {}, true},
                                {"section_phi"}, {"section_theta"}, {"section_sheet", 1, true}};
  for (const auto& r : rows) {
    const PeriodicOrbit& o = r.orbit;
    c[0].whole.push_back(r.family), c[1].whole.push_back(r.index);
    c[2].real.push_back(o.l), c[3].real.push_back(o.h), c[4].real.push_back(o.period);
    for (int k = 0; k < 3; ++k) c[5].real.push_back(o.x0(k)), c[6].real.push_back(o.x0(k + 3));
    c[7].real.push_back(o.residual);
    for (const auto& m : o.multipliers) c[8].real.push_back(m.real()), c[8].real.push_back(m.imag());
    c[9].text.push_back(o.stability), c[10].text.push_back(r.event);
    c[11].whole.push_back(o.degenerate ? 1 : 0), c[12].whole.push_back(r.equilibrium);
    c[13].real.push_back(r.omega), c[14].real.push_back(o.trivial_deviation), c[15].real.push_back(o.product_deviation);
    c[16].whole.push_back(r.parent), c[17].real.push_back(o.reduced_trace), c[18].real.push_back(o.invariance_defect);
    c[19].text.push_back(r.family_end);
    const SectionPoint p = section ? section_coordinates(body, *section, o.x0) : SectionPoint{NAN, NAN, 0};
    c[20].real.push_back(p.phi), c[21].real.push_back(p.theta), c[22].whole.push_back(p.sheet);
  }
  append_appelrot_columns(body, rows, c);  // k, appelrot_family, appelrot_distance, critical_rank_gap
  return c;
}

TableGroup manifold_group(const std::vector<RowManifolds>& all) {
  TableGroup g{"manifolds", {{"family", 1, true}, {"index", 1, true}, {"branch", 1, false, {}, {}, {}, true},
                             {"side", 1, true}, {"point", 1, true}, {"s"}, {"crossing", 1, true}, {"t"},
                             {"phi"}, {"theta"}, {"sheet", 1, true}, {"angular_momentum", 3}, {"gamma", 3},
                             {"multiplier"}, {"returns", 1, true}}};
  auto& c = g.columns;
  for (const RowManifolds& r : all)
    for (const ManifoldPoint& p : r.m.points) {
      c[0].whole.push_back(r.family), c[1].whole.push_back(r.index);
      c[2].text.push_back(p.branch == 0 ? "unstable" : "stable");
      c[3].whole.push_back(p.side), c[4].whole.push_back(p.point), c[5].real.push_back(p.s);
      c[6].whole.push_back(p.crossing), c[7].real.push_back(p.t);
      c[8].real.push_back(p.at.phi), c[9].real.push_back(p.at.theta), c[10].whole.push_back(p.at.sheet);
      for (int k = 0; k < 3; ++k) c[11].real.push_back(p.x(k)), c[12].real.push_back(p.x(k + 3));
      c[13].real.push_back(r.m.lambda), c[14].whole.push_back(r.m.returns);
    }
  return g;
}

}  // namespace lgi::experiments

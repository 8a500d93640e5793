#include "experiments/commands/periodic/periodic_tables.hpp"

#include <cmath>

#include "experiments/commands/periodic/critical_seeds.hpp"

namespace lgi::experiments {

namespace {

/// A Cardan top's columns: the Kovalevskaya ones do not apply (NaN, −1); its state q, p and q1's drift.
void append_cardan_columns(const std::vector<FamilyOrbit>& rows, std::vector<TableColumn>& c) {
  TableColumn k{"k"}, family{"appelrot_family", 1, true}, distance{"appelrot_distance"}, gap{"critical_rank_gap"};
  TableColumn q{"cardan_angles", 3}, p{"cardan_momenta", 3}, drift{"cardan_drift"};
  for (const FamilyOrbit& r : rows) {
    k.real.push_back(NAN), family.whole.push_back(-1), distance.real.push_back(NAN), gap.real.push_back(NAN);
    for (int j = 0; j < 3; ++j) q.real.push_back(r.orbit.x0(j)), p.real.push_back(r.orbit.x0(j + 3));
    drift.real.push_back(r.orbit.drift);
  }
  for (TableColumn* col : {&k, &family, &distance, &gap, &q, &p, &drift}) c.push_back(std::move(*col));
}

/// The body's (Π, Γ) at an orbit's point: x0 itself, or from (q, p) on a Cardan top.
Vec6 body_point(const PeriodicFlow& flow, const Vec6& x0) {
  if (!flow.cardan) return x0;
  const system::TorusState s = system::unstack(x0);
  const lie::SO3xR3 b = flow.cardan->body_state(s);
  Vec6 x;
  x << b.Pi, b.R.transpose() * Vec3::UnitZ();
  return x;
}

}  // namespace

std::vector<TableColumn> periodic_columns(const PeriodicFlow& flow, const std::vector<FamilyOrbit>& rows,
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
    const Vec6 x = body_point(flow, o.x0);
    for (int k = 0; k < 3; ++k) c[5].real.push_back(x(k)), c[6].real.push_back(x(k + 3));
    c[7].real.push_back(o.residual);
    for (const auto& m : o.multipliers) c[8].real.push_back(m.real()), c[8].real.push_back(m.imag());
    c[9].text.push_back(o.stability), c[10].text.push_back(r.event);
    c[11].whole.push_back(o.degenerate ? 1 : 0), c[12].whole.push_back(r.equilibrium);
    c[13].real.push_back(r.omega), c[14].real.push_back(o.trivial_deviation), c[15].real.push_back(o.product_deviation);
    c[16].whole.push_back(r.parent), c[17].real.push_back(o.reduced_trace), c[18].real.push_back(o.invariance_defect);
    c[19].text.push_back(r.family_end);
    const SectionPoint p = section ? section_coordinates(flow, *section, o.x0) : SectionPoint{NAN, NAN, 0};
    c[20].real.push_back(p.phi), c[21].real.push_back(p.theta), c[22].whole.push_back(p.sheet);
  }
  if (flow.cardan)
    append_cardan_columns(rows, c);
  else
    append_appelrot_columns(flow.body, rows, c);  // k, appelrot_family, appelrot_distance, critical_rank_gap
  // Last, for every top: how many factors the multipliers were read from (periodic_orbit.hpp, classify_orbit).
  TableColumn pieces{"monodromy_pieces", 1, true};
  for (const auto& r : rows) pieces.whole.push_back(static_cast<std::int64_t>(r.orbit.pieces.size()));
  c.push_back(std::move(pieces));
  return c;
}

TableGroup manifold_group(const PeriodicFlow& flow, const std::vector<RowManifolds>& all) {
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
      const Vec6 x = body_point(flow, p.x);
      for (int k = 0; k < 3; ++k) c[11].real.push_back(x(k)), c[12].real.push_back(x(k + 3));
      c[13].real.push_back(r.m.lambda), c[14].whole.push_back(r.m.returns);
    }
  if (flow.cardan) {
    TableColumn q{"cardan_angles", 3}, p{"cardan_momenta", 3};
    for (const RowManifolds& r : all)
      for (const ManifoldPoint& m : r.m.points)
        for (int k = 0; k < 3; ++k) q.real.push_back(m.x(k)), p.real.push_back(m.x(k + 3));
    c.push_back(std::move(q)), c.push_back(std::move(p));
  }
  return g;
}

}  // namespace lgi::experiments

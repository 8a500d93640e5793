#include "experiments/commands/periodic/periodic_run.hpp"

#include <algorithm>
#include <cmath>

#include "experiments/commands/periodic/critical_seeds.hpp"
#include "experiments/commands/periodic/periodic_seeds.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/errors/input_error.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/scene_suspension.hpp"

namespace lgi::experiments {

namespace {

/// The families of the seeds (of a seed file or a poincare file), numbered from 0.
/// `seed_done` as PeriodicRequest::start_done: after each seed; false drops it and stops.
std::vector<FamilyOrbit> seed_families(const PeriodicFlow& body, const std::vector<SectionSeed>& seeds, double l,
                                       double direction, const FamilySettings& s, std::vector<std::string>& failures,
                                       const PeriodicRequest::StartDone& seed_done, bool& stopped) {
  std::vector<FamilyOrbit> rows;
  int family = 0;
  for (std::size_t k = 0; k < seeds.size(); ++k) {
    const std::size_t failures_before = failures.size();
    const SectionSeed& seed = seeds[k];
    std::vector<FamilyOrbit> f;
    if (!seed.failure.empty()) {
      failures.push_back(seed.failure);
    } else {
      const double h = std::isnan(seed.h) ? flow_invariants(body, seed.x).value(0) : seed.h;
      FamilySettings own = s;  // a seed's own phase condition (a Cardan top's factor of its piece)
      if (seed.section) own.shooting.section = seed.section;
      f = continue_family(body, seed.x, seed.period, h, l, direction, family, own, failures);
    }
    if (seed_done && !seed_done(k + 1, seeds.size())) {  // the signal may have cut this seed short: dropped
      failures.resize(failures_before);
      stopped = true;
      return rows;
    }
    for (const auto& r : f) family = std::max(family, r.family + 1);
    rows.insert(rows.end(), f.begin(), f.end());
  }
  return rows;
}

/// The manifolds of each family's first orbit that is hyperbolic.
std::vector<RowManifolds> manifolds_of(const PeriodicFlow& body, const PhaseSection& section,
                                       const std::vector<FamilyOrbit>& rows, const ManifoldSettings& ms,
                                       std::vector<std::string>& failures) {
  std::vector<RowManifolds> out;
  for (const FamilyOrbit& r : rows) {
    if (r.index != 0 || r.orbit.stability == "elliptic") continue;
    RowManifolds m{r.family, r.index, orbit_manifolds(body, section, r.orbit, ms)};
    if (!m.m.why_not.empty())
      failures.push_back("manifolds of family " + std::to_string(r.family) + ": " + m.m.why_not);
    else
      out.push_back(std::move(m));
  }
  return out;
}

/// The seeds of a Cardan top: q1 set to 0 (it is cyclic), p1 checked against ℓ.
std::vector<SectionSeed> cardan_seeds(const std::vector<std::pair<Vec6, double>>& seeds, double l) {
  std::vector<SectionSeed> out;
  for (std::size_t k = 0; k < seeds.size(); ++k) {
    Vec6 x = seeds[k].first;
    if (std::abs(x(3) - l) > 1e-9 * std::max(1.0, std::abs(l)))
      throw UsageError("--seed-file: seed " + std::to_string(k + 1) + " has p1 = " + format_general(x(3), 17) +
                       ", not --l " + format_general(l, 17) + " (a Cardan seed is q1 q2 q3 p1 p2 p3 T)");
    x(0) = 0.0, x(3) = l;
    out.push_back({x, seeds[k].second, "seed " + std::to_string(k + 1), ""});
  }
  return out;
}

/// The families of the seeds of a poincare file on its section, and their manifolds.
void section_families(const PeriodicFlow& flow, const PeriodicRequest& r, PeriodicResult& out);

/// A Cardan top's families: its relative equilibria's Lyapunov families, seeds, or a section's seeds.
void cardan_families(const PeriodicFlow& flow, const PeriodicRequest& r, PeriodicResult& out) {
  if (!r.critical.empty()) throw UsageError("--from-critical: a Kovalevskaya top only, not a Cardan top");
  if (!r.poincare.empty()) return section_families(flow, r, out);
  out.l = r.l.value_or(0.0);
  if (r.from_equilibria)
    out.rows = cardan_lyapunov_families(*flow.cardan, out.l, r.settings, out.failures, r.direction, r.start_done);
  else
    out.rows = seed_families(flow, cardan_seeds(r.seeds, out.l), out.l, r.direction, r.settings, out.failures,
                             r.start_done, out.stopped);
}

/// Refuses (UsageError naming --seeds-from-poincare) a Cardan file of another top than `top`: its
/// /parameters scene_toml must give the same mechanism, parameter for parameter.
void check_same_cardan_top(const system::CardanTop& top, const PoincareFile& f, const PeriodicRequest& r) {
  std::optional<system::CardanTop> other;
  try {
    const system::Scene scene = parse_scene(f.scene_toml, r.poincare + " /parameters scene_toml");
    if (scene.suspension) other.emplace(cardan_top(scene));
  } catch (const InputError& e) {
    throw UsageError(std::string("--seeds-from-poincare: ") + e.what());
  }
  const auto& a = top.suspension;
  const bool same = other && other->J == top.J && other->mass == top.mass && other->chi == top.chi &&
                    other->g == top.g && other->suspension.tilt == a.tilt &&
                    other->suspension.outer_inertia == a.outer_inertia &&
                    other->suspension.inner_inertia == a.inner_inertia && other->suspension.outer_mass == a.outer_mass &&
                    other->suspension.outer_center == a.outer_center && other->suspension.inner_mass == a.inner_mass &&
                    other->suspension.inner_center == a.inner_center;
  if (!same)
    throw UsageError("--seeds-from-poincare: " + r.poincare + " was written for another top than --scene " +
                     r.scene_file + " (its /parameters scene_toml gives a different mechanism)");
}

/// The poincare file of --seeds-from-poincare, refused (UsageError naming the flag) unless it is of
/// `flow`'s kind of top at --l; a Cardan top's file must hold the same top (its scene_toml's).
PoincareFile section_file(const PeriodicFlow& flow, const PeriodicRequest& r) {
  const PoincareFile f = [&] {
    try {
      return read_poincare_file(r.poincare);
    } catch (const InputError& e) {
      throw UsageError(std::string("--seeds-from-poincare: ") + e.what());
    }
  }();
  if (f.cardan != (flow.cardan != nullptr))
    throw UsageError("--seeds-from-poincare: " + r.poincare + " is the section of " +
                     (f.cardan ? "a Cardan top" : "a heavy top") + ", and --scene " + r.scene_file + " is " +
                     (flow.cardan ? "a Cardan top" : "a heavy top"));
  if (flow.cardan) check_same_cardan_top(*flow.cardan, f, r);
  if (r.l && std::abs(*r.l - f.l) > 1e-12 * std::max(1.0, std::abs(f.l)))
    throw UsageError("--l: " + format_general(*r.l, 17) + " differs from the l of --seeds-from-poincare " + r.poincare +
                     " (" + format_general(f.l, 17) + "); leave --l out");
  return f;
}

void section_families(const PeriodicFlow& flow, const PeriodicRequest& r, PeriodicResult& out) {
  const PoincareFile f = section_file(flow, r);
  const FamilySettings& s = r.settings;
  out.l = f.l;
  FamilySettings on_section = s;
  on_section.shooting.section = section_of(f);
  out.section = on_section.shooting.section;
  // Every seed is put at the file's level; its family starts at the file's h.
  std::vector<SectionSeed> seeds = poincare_seeds(flow, f, r.poincare_rows, r.poincare_points, r.returns,
                                                  s.shooting.dt, 500.0 * r.returns);
  for (SectionSeed& seed : seeds) {
    const PhaseSection phase = seed.section.value_or(*out.section);
    if (seed.failure.empty() && !project_to_level(flow, seed.x, f.h, f.l, &phase))
      seed.failure = seed.label + ": cannot be put on the level and the section";
  }
  out.rows = seed_families(flow, seeds, out.l, r.direction, on_section, out.failures, r.start_done, out.stopped);
  if (r.manifolds.points > 0 && !out.stopped)
    out.manifolds = manifolds_of(flow, *out.section, out.rows, r.manifolds, out.failures);
}

}  // namespace

PeriodicResult periodic_families(const PeriodicFlow& flow, const PeriodicRequest& request) {
  const HeavyTopBody& body = flow.body;
  PeriodicResult out;
  // The caller's start_done, counting the starts kept for the result.
  PeriodicRequest r = request;
  if (request.start_done)
    r.start_done = [&out, &request](std::size_t done, std::size_t total) {
      out.starts = total;
      const bool go_on = request.start_done(done, total);
      out.starts_kept = go_on ? done : done - 1;
      out.stopped = !go_on;
      return go_on;
    };
  if (flow.cardan) {
    cardan_families(flow, r, out);
    return out;
  }
  out.l = r.l.value_or(0.0);
  const FamilySettings& s = r.settings;
  bool& stopped = out.stopped;
  if (r.from_equilibria) {
    out.rows = lyapunov_families(body, out.l, s, out.failures, r.direction, r.start_done);
    return out;
  }
  if (!r.critical.empty()) {
    const std::vector<SectionSeed> seeds = critical_seeds(body, r.scene_file, out.l, r.critical, s.shooting.dt);
    out.rows = seed_families(body, seeds, out.l, r.direction, s, out.failures, r.start_done, stopped);
    return out;
  }
  if (r.poincare.empty()) {
    std::vector<SectionSeed> seeds;
    for (const auto& [x, T] : r.seeds) seeds.push_back({x, T, "", ""});
    out.rows = seed_families(body, seeds, out.l, r.direction, s, out.failures, r.start_done, stopped);
    return out;
  }
  section_families(flow, r, out);
  return out;
}

std::string cardan_tilt_refusal(const system::CardanTop& top, const std::string& scene_file) {
  if (top.outer_angle_cyclic()) return "";
  return scene_file + ": suspension.tilt = " + format_general(top.suspension.tilt, 17) +
         ": a tilted outer axis under gravity leaves no cyclic angle (p1 is no integral), so there is no "
         "reduced flow at fixed --l; lgi periodic on a Cardan top needs tilt = 0";
}

}  // namespace lgi::experiments

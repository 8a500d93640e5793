// The accessible region on the Poisson sphere and the topology of the energy
// surface (experiments/analysis/accessible_region.hpp, docs/atlas.md §8):
//  - the critical points of U_l are the relative equilibria at l, their
//    values the equilibria's h, and their Morse indices add up to the Euler
//    characteristic of the sphere; the minima are the energy–Casimir stable ones;
//  - the free body (Euler): 2S3, S1xS2, RP3 between the principal-axis energies;
//  - Lagrange tops: the topology at every (l, h) of a raster agrees with the
//    one-dimensional count of intervals of {u = cos(theta) : U_l(u) <= h}
//    (a cap around one pole is S3, two caps 2S3, a band S1xS2, all RP3);
//  - the general top: the grid's Euler characteristic equals the Morse count
//    on almost every cell, and the static top (l = 0) is S3 then RP3.
#include <catch2/catch.hpp>
#include <cmath>
#include <map>

#include "experiments/analysis/accessible_region.hpp"
#include "support/shipped_scene.hpp"

namespace test_accessible_region {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using experiments::HeavyTopBody;

namespace {

HeavyTopBody top(const lie::Vec3& J, const lie::Vec3& weight) {
  HeavyTopBody b;
  b.J = J.asDiagonal();
  b.weight = weight;
  return b;
}

std::string topology_at(const HeavyTopBody& body, double l, double h, int grid = 90) {
  const auto critical = experiments::critical_points(body, l);
  const auto region = experiments::accessible_region(experiments::potential_grid(body, l, grid), critical, h);
  return region.topology;
}

/// The Lagrange top's energy surface from U_l(u), u = cos(theta) (A1 = A2 = A,
/// A3 = C, m g chi = (0, 0, w)): the intervals of {U_l <= h} on a fine u grid.
std::string lagrange_topology(double A, double C, double w, double l, double h) {
  constexpr int n = 200001;
  std::vector<std::string> names;
  int start = -1;
  for (int k = 0; k <= n; ++k) {
    const double u = k < n ? -1.0 + 2.0 * k / (n - 1) : 2.0;
    const bool in = k < n && l * l / (2.0 * (A + (C - A) * u * u)) + w * u <= h;
    if (in && start < 0) start = k;
    if (!in && start >= 0) {
      const bool south = start == 0, north = k == n;
      names.push_back(south && north ? "RP3" : south || north ? "S3" : "S1xS2");
      start = -1;
    }
  }
  return experiments::energy_surface_topology(names);
}

}  // namespace

TEST_CASE("critical points of U_l are the relative equilibria at l, with Morse indices", "[region]") {
  const auto scene = testing::shipped_scene("general_top_richter");
  const HeavyTopBody body = experiments::heavy_top_of(scene, "region");
  for (const double l : {0.0, 0.5, 1.0, 2.0, 3.0, 4.5}) {
    INFO("l = " << l);
    const auto critical = experiments::critical_points(body, l);
    const auto eq = experiments::equilibria_at(body, l);
    REQUIRE(critical.points.size() == eq.rows.size());
    int euler = 0, minima = 0, stable = 0;
    for (std::size_t k = 0; k < eq.rows.size(); ++k) {
      const auto& c = critical.points[k];
      CHECK((c.gamma - eq.rows[k].gamma).norm() == 0.0);
      CHECK(std::abs(c.value - eq.rows[k].h) <= 1e-13 * (1.0 + std::abs(c.value)));
      CHECK(!c.circle);
      euler += c.index == 1 ? -1 : 1;
      minima += c.index == 0 ? 1 : 0;
      stable += eq.rows[k].nonlinearly_stable ? 1 : 0;
    }
    CHECK(euler == 2);
    CHECK(minima == stable);
  }
}

TEST_CASE("the free body: 2S3, S1xS2, RP3 between the principal-axis energies", "[region]") {
  const HeavyTopBody body = top({1.0, 2.0, 3.0}, lie::Vec3::Zero());
  const double l = 1.5, e3 = l * l / 6.0, e2 = l * l / 4.0, e1 = l * l / 2.0;
  CHECK(topology_at(body, l, 0.5 * (e3 + e2)) == "2S3");
  CHECK(topology_at(body, l, 0.5 * (e2 + e1)) == "S1xS2");
  CHECK(topology_at(body, l, 1.1 * e1) == "RP3");
  CHECK(topology_at(body, l, 0.9 * e3) == "empty");
  CHECK(topology_at(body, 0.0, 1.0) == "RP3");  // U_0 = 0: the whole sphere
  const auto region =
      experiments::accessible_region(experiments::potential_grid(body, l, 60), experiments::critical_points(body, l),
                                     0.5 * (e3 + e2));
  REQUIRE(region.components.size() == 2);
  CHECK(region.resolved);
  for (const auto& c : region.components) {
    CHECK(c.boundaries == 1);
    CHECK(c.minima == 1);  // a disc around ±e3
    CHECK(c.euler_morse == 1);
  }
}

TEST_CASE("Lagrange tops: the topology agrees with the intervals of U_l(cos theta) <= h", "[region]") {
  for (const double A : {1.0, 0.9, 0.6}) {  // the seed's cigar, 3/4 < alpha < 1 and disk (alpha = A/C, C = 1 or 0.5)
    const double C = A == 1.0 ? 0.5 : 1.0;
    const HeavyTopBody body = top({A, A, C}, {0.0, 0.0, 1.0});
    std::map<std::string, int> seen;
    int agree = 0, cells = 0, resolved = 0;
    for (int i = 0; i < 12; ++i) {
      const double l = 0.25 + 0.35 * i;
      const auto critical = experiments::critical_points(body, l);
      const auto grid = experiments::potential_grid(body, l, 90);
      std::vector<double> hs;
      for (int j = 0; j < 40; ++j) hs.push_back(-1.2 + 0.2 * j);
      const auto summary = experiments::region_summaries(grid, critical, hs);
      for (std::size_t j = 0; j < hs.size(); ++j) {
        const std::string expected = lagrange_topology(A, C, 1.0, l, hs[j]);
        ++cells;
        ++seen[expected];
        if (!summary[j].resolved) continue;  // a band or cap thinner than the grid: flagged, not named
        ++resolved;
        agree += summary[j].topology == expected ? 1 : 0;
        if (summary[j].topology != expected)
          WARN("A = " << A << " l = " << l << " h = " << hs[j] << ": " << summary[j].topology << " vs " << expected);
      }
    }
    INFO("A = " << A);
    CHECK(agree == resolved);
    CHECK(resolved >= cells * 97 / 100);
    CHECK(seen.count("S3"));
    CHECK(seen.count("RP3"));
    if (A == 1.0) CHECK(seen.count("S1xS2"));  // cigar: the band around the equator
    if (A == 0.6) CHECK(seen.count("2S3"));    // disk: two caps at high l (for A = 0.9 only beyond l^2 = 10)
  }
}

TEST_CASE("the general top: the grid agrees with Morse theory, the static top is S3 then RP3", "[region]") {
  const auto scene = testing::shipped_scene("general_top_richter");
  const HeavyTopBody body = experiments::heavy_top_of(scene, "region");
  const double w = body.weight.norm();
  CHECK(topology_at(body, 0.0, 0.0) == "S3");
  CHECK(topology_at(body, 0.0, 1.01 * w) == "RP3");
  int resolved = 0, cells = 0;
  std::map<std::string, int> seen;
  for (int i = 0; i < 16; ++i) {
    const double l = 0.3 * i;
    std::vector<double> hs;
    for (int j = 0; j < 50; ++j) hs.push_back(-1.0 + 0.12 * j);
    const auto summary = experiments::region_summaries(experiments::potential_grid(body, l, 90),
                                                       experiments::critical_points(body, l), hs);
    for (const auto& s : summary) {
      ++cells;
      resolved += s.resolved ? 1 : 0;
      ++seen[s.topology];
      if (s.resolved) CHECK(s.euler == s.euler_morse);
    }
  }
  CHECK(resolved >= cells * 97 / 100);
  for (const char* name : {"empty", "S3", "RP3", "S1xS2"}) {
    INFO(name);
    CHECK(seen.count(name));
  }
}

TEST_CASE("component and energy-surface names", "[region]") {
  CHECK(experiments::component_topology(0) == "RP3");
  CHECK(experiments::component_topology(1) == "S3");
  CHECK(experiments::component_topology(2) == "S1xS2");
  CHECK(experiments::component_topology(4) == "#3(S1xS2)");
  CHECK(experiments::energy_surface_topology({}) == "empty");
  CHECK(experiments::energy_surface_topology({"S3", "S3"}) == "2S3");
  CHECK(experiments::energy_surface_topology({"S1xS2", "S3"}) == "S3 + S1xS2");
  CHECK(experiments::energy_surface_topology({"S1xS2", "S1xS2"}) == "2(S1xS2)");
}

TEST_CASE("the Kovalevskaya top at l = 2: a degenerate critical point, not an unresolved grid", "[region]") {
  // J = (2, 2, 1), m g chi = (1, 0, 0): at l = 2 the family Gamma = (1/w^2, 0, +-sqrt(1 - w^-4)) leaves the
  // rotation about e1 (w = 1, Gamma = e1, h = 2): U_l has a degenerate critical point there (docs/atlas.md §8).
  const HeavyTopBody body = top({2.0, 2.0, 1.0}, {1.0, 0.0, 0.0});
  const auto critical = experiments::critical_points(body, 2.0);
  int degenerate = 0;
  for (const auto& c : critical.points) {
    CHECK_FALSE(c.circle);
    if (c.degenerate) {
      ++degenerate;
      CHECK((c.gamma - lie::Vec3::UnitX()).norm() <= 1e-6);
    }
  }
  CHECK(degenerate >= 1);
  for (const int grid : {90, 240}) {
    const auto region = experiments::accessible_region(experiments::potential_grid(body, 2.0, grid), critical, 2.5);
    CHECK(region.degenerate);
    CHECK(region.resolved);
  }
  // Away from it the count applies again.
  const auto near = experiments::critical_points(body, 2.2);
  for (const auto& c : near.points) CHECK_FALSE(c.degenerate);
  const auto region = experiments::accessible_region(experiments::potential_grid(body, 2.2, 90), near, 2.5);
  CHECK_FALSE(region.degenerate);
  CHECK(region.resolved);
}

TEST_CASE("a polled row: the same cells as without the polls; a false poll stops it with no result", "[region]") {
  // At grid 300 the row has more than 2^20 simplices: the polled sort is a merge of sorted pieces.
  const auto scene = testing::shipped_scene("general_top_richter");
  const HeavyTopBody body = experiments::heavy_top_of(scene, "region");
  const double l = 1.5;
  std::vector<double> hs;
  for (int j = 0; j < 30; ++j) hs.push_back(-1.0 + 0.12 * j);
  const auto grid = experiments::potential_grid(body, l, 300);
  const auto critical = experiments::critical_points(body, l);
  const auto plain = experiments::region_summaries(grid, critical, hs);
  int polls = 0;
  std::size_t last_done = 0;
  const auto polled = experiments::region_summaries(grid, critical, hs, [&](std::size_t done) {
    ++polls, last_done = done;
    return true;
  });
  REQUIRE(polled.size() == plain.size());
  for (std::size_t j = 0; j < hs.size(); ++j) {
    CHECK(polled[j].topology == plain[j].topology);
    CHECK(polled[j].euler == plain[j].euler);
    CHECK(polled[j].components == plain[j].components);
    CHECK(polled[j].resolved == plain[j].resolved);
  }
  CHECK(polls > static_cast<int>(hs.size()));  // within the row too
  CHECK(last_done == hs.size() - 1);            // the last poll: before the last cell
  int left = 5;
  CHECK(experiments::region_summaries(grid, critical, hs, [&](std::size_t) { return --left > 0; }).empty());
  CHECK(experiments::potential_grid(body, l, 300, [] { return false; }).n == 0);
}
}  // namespace test_accessible_region

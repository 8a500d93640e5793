// The accessible region on the Poisson sphere and the topology of the energy
// surface (accessible_region.hpp; docs/atlas.md §8).
#include "experiments/analysis/accessible_region.hpp"

#include <optional>
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <numbers>

#include "experiments/errors/input_error.hpp"

namespace lgi::experiments {

namespace {

/// A poll of the caller's stop flag (region_summaries' keep_going); false stops the work:
/// it throws Stopped, which region_summaries catches. Empty: never stops.
using Poll = std::function<bool()>;
struct Stopped {};
void check(const Poll& poll) {
  if (poll && !poll()) throw Stopped{};
}
constexpr std::size_t poll_every = std::size_t{1} << 20;  // simplices between two polls: well under 0.1 s

/// The triangulation of a SphereGrid: the pole rows are one vertex each;
/// between two rings every quad is cut along (i, j)–(i+1, j+1); the poles
/// are joined to their neighbouring ring by fans. V − E + F = 2.
struct Triangulation {
  int n = 0, m = 0;
  std::vector<double> value, area;  // per vertex; area as a fraction of the sphere
  std::vector<std::array<int, 2>> edges;
  std::vector<std::array<int, 3>> triangles;
  int vertex(int i, int j) const {
    if (i == 0) return 0;
    if (i == n) return 1 + (n - 1) * m;
    return 1 + (i - 1) * m + ((j % m) + m) % m;
  }
};

Triangulation triangulate(const SphereGrid& g, const Poll& poll = {}) {
  Triangulation t;
  t.n = g.n, t.m = g.meridians();
  const int vertices = 2 + (t.n - 1) * t.m;
  t.value.assign(static_cast<std::size_t>(vertices), 0.0);
  t.area.assign(static_cast<std::size_t>(vertices), 0.0);
  t.edges.reserve(3 * static_cast<std::size_t>(vertices));
  t.triangles.reserve(2 * static_cast<std::size_t>(vertices));
  const double half = 0.5 * std::numbers::pi / t.n;
  for (int i = 0; i <= t.n; ++i) {
    check(poll);
    for (int j = 0; j < t.m; ++j) {
      const auto v = static_cast<std::size_t>(t.vertex(i, j));
      t.value[v] = g.at(i, j);
      if (i == 0 || i == t.n) t.area[v] = 0.5 * (1.0 - std::cos(half));
      else t.area[v] = 0.5 * (std::cos(g.theta(i) - half) - std::cos(g.theta(i) + half)) / t.m;
    }
  }
  for (int i = 1; i < t.n; ++i) {
    check(poll);  // a ring: at most 4000 quads
    for (int j = 0; j < t.m; ++j) {
      const int a = t.vertex(i, j), b = t.vertex(i, j + 1);
      t.edges.push_back({a, b});
      if (i == 1) {
        t.edges.push_back({0, a});
        t.triangles.push_back({0, a, b});
      }
      if (i == t.n - 1) {
        const int s = t.vertex(t.n, 0);
        t.edges.push_back({a, s});
        t.triangles.push_back({a, b, s});
        continue;
      }
      const int c = t.vertex(i + 1, j), d = t.vertex(i + 1, j + 1);
      t.edges.push_back({a, c});
      t.edges.push_back({a, d});
      t.triangles.push_back({a, b, d});
      t.triangles.push_back({a, c, d});
    }
  }
  return t;
}

/// A simplex in the order it enters the sublevel sets: by value (the largest
/// of its vertices'), vertices before edges before triangles.
struct Entry {
  double value;
  int dim, index;
};

/// std::stable_sort in pieces of poll_every entries, then a bottom-up merge sort of the
/// pieces (ties from the left run first: the same order, a stable sort's result being
/// unique), with a poll after each piece and every poll_every entries merged.
template <class Less>
void stable_sort_polled(std::vector<Entry>& v, Less less, const Poll& poll) {
  const std::size_t n = v.size();
  for (std::size_t a = 0; a < n; a += poll_every) {
    std::stable_sort(v.begin() + static_cast<std::ptrdiff_t>(a),
                     v.begin() + static_cast<std::ptrdiff_t>(std::min(n, a + poll_every)), less);
    check(poll);
  }
  std::vector<Entry> to;
  to.reserve(n);  // filled by push_back: its pages are touched (slowly, at first) between the polls
  for (std::size_t width = poll_every; width < n; width *= 2) {
    to.clear();
    for (std::size_t a = 0; a < n; a += 2 * width) {
      const std::size_t mid = std::min(n, a + width), end = std::min(n, a + 2 * width);
      for (std::size_t i = a, j = mid; i < mid || j < end;) {
        to.push_back(j < end && (i == mid || less(v[j], v[i])) ? v[j++] : v[i++]);
        if (to.size() % poll_every == 0) check(poll);
      }
    }
    v.swap(to);
  }
}

std::vector<Entry> entry_order(const Triangulation& t, const Poll& poll = {}) {
  std::vector<Entry> order;
  order.reserve(t.value.size() + t.edges.size() + t.triangles.size());
  for (std::size_t v = 0; v < t.value.size(); ++v) order.push_back({t.value[v], 0, static_cast<int>(v)});
  for (std::size_t e = 0; e < t.edges.size(); ++e) {
    if (e % poll_every == 0) check(poll);
    const auto& [a, b] = t.edges[e];
    order.push_back({std::max(t.value[static_cast<std::size_t>(a)], t.value[static_cast<std::size_t>(b)]), 1,
                     static_cast<int>(e)});
  }
  for (std::size_t f = 0; f < t.triangles.size(); ++f) {
    if (f % poll_every == 0) check(poll);
    double v = -INFINITY;
    for (int k : t.triangles[f]) v = std::max(v, t.value[static_cast<std::size_t>(k)]);
    order.push_back({v, 2, static_cast<int>(f)});
  }
  const auto less = [](const Entry& a, const Entry& b) { return a.value != b.value ? a.value < b.value : a.dim < b.dim; };
  if (poll) stable_sort_polled(order, less, poll);
  else std::stable_sort(order.begin(), order.end(), less);
  return order;
}

/// The components of a growing sub-complex (union–find; the older root, the
/// component with the lower minimum, survives a merge), each with its Euler
/// characteristic and area.
class ComponentSweep {
 public:
  ComponentSweep(const Triangulation& t, std::vector<Entry> order, Poll poll = {})
      : t_(t), order_(std::move(order)), poll_(std::move(poll)) {
    parent_.assign(t.value.size(), -1);
    euler_.assign(t.value.size(), 0);
    area_.assign(t.value.size(), 0.0);
  }
  /// Adds every simplex with value ≤ h (h non-decreasing between calls).
  void advance_to(double h) {
    for (; next_ < order_.size() && order_[next_].value <= h; ++next_) {
      if (next_ % poll_every == 0) check(poll_);
      const Entry& s = order_[next_];
      if (s.dim == 0) {
        const auto v = static_cast<std::size_t>(s.index);
        parent_[v] = s.index, euler_[v] = 1, area_[v] = t_.area[v];
        roots_.push_back(s.index);
      } else if (s.dim == 1) {
        const auto& [a, b] = t_.edges[static_cast<std::size_t>(s.index)];
        join(find(a), find(b));
      } else {
        euler_[static_cast<std::size_t>(find(t_.triangles[static_cast<std::size_t>(s.index)][0]))] += 1;
      }
    }
  }
  bool present(int v) const { return parent_[static_cast<std::size_t>(v)] >= 0; }
  int find(int v) {
    auto k = static_cast<std::size_t>(v);
    while (parent_[k] != static_cast<int>(k)) {
      parent_[k] = parent_[static_cast<std::size_t>(parent_[k])];
      k = static_cast<std::size_t>(parent_[k]);
    }
    return static_cast<int>(k);
  }
  /// The roots in order of birth (lowest minimum first).
  const std::vector<int>& roots() const { return roots_; }
  int euler(int root) const { return euler_[static_cast<std::size_t>(root)]; }
  double area(int root) const { return area_[static_cast<std::size_t>(root)]; }

 private:
  void join(int a, int b) {
    if (a == b) {
      euler_[static_cast<std::size_t>(a)] -= 1;  // an edge closing a loop
      return;
    }
    const auto ia = std::find(roots_.begin(), roots_.end(), a), ib = std::find(roots_.begin(), roots_.end(), b);
    if (ib < ia) std::swap(a, b);  // keep the older root
    euler_[static_cast<std::size_t>(a)] += euler_[static_cast<std::size_t>(b)] - 1;
    area_[static_cast<std::size_t>(a)] += area_[static_cast<std::size_t>(b)];
    parent_[static_cast<std::size_t>(b)] = a;
    roots_.erase(std::find(roots_.begin(), roots_.end(), b));
  }
  const Triangulation& t_;
  std::vector<Entry> order_;
  Poll poll_;
  std::size_t next_ = 0;
  std::vector<int> parent_, euler_;
  std::vector<double> area_;
  std::vector<int> roots_;
};

/// The grid vertex nearest to a direction.
int nearest_vertex(const Triangulation& t, const Vec3& g) {
  const double theta = std::acos(std::clamp(g.z() / g.norm(), -1.0, 1.0));
  double phi = std::atan2(g.y(), g.x());
  if (phi < 0.0) phi += 2.0 * std::numbers::pi;
  const int i = static_cast<int>(std::lround(theta * t.n / std::numbers::pi));
  const int j = static_cast<int>(std::lround(phi * t.n / std::numbers::pi));
  return t.vertex(std::clamp(i, 0, t.n), j);
}

/// The Morse count of every component at energy h (critical points below h,
/// each put in the component of its nearest grid vertex); false if one of
/// them falls outside the sub-complex.
struct MorseCount {
  int minima = 0, saddles = 0, maxima = 0, circles = 0, euler = 0, degenerate = 0;
};
bool morse_counts(const Triangulation& t, ComponentSweep& sweep, const CriticalSet& critical, double h,
                  std::map<int, MorseCount>& out) {
  bool placed = true;
  for (const auto& c : critical.points) {
    if (!(c.value < h)) continue;
    const int v = nearest_vertex(t, c.gamma);
    if (!sweep.present(v)) {
      placed = false;
      continue;
    }
    MorseCount& m = out[sweep.find(v)];
    if (c.circle) {
      ++m.circles;
      continue;
    }
    if (c.degenerate) {
      ++m.degenerate;
      continue;
    }
    (c.index == 0 ? m.minima : c.index == 1 ? m.saddles : m.maxima) += 1;
    m.euler += c.index == 1 ? -1 : 1;
  }
  return placed;
}

/// Canonical order of the names: S3, S1xS2, #k(S1xS2) by k, RP3.
int name_rank(const std::string& s) {
  if (s == "S3") return 0;
  if (s == "S1xS2") return 1;
  if (s == "RP3") return 1 << 20;
  return 2 + std::atoi(s.c_str() + 1);  // "#k(S1xS2)"
}

}  // namespace

HeavyTopBody heavy_top_of(const system::Scene& scene, const std::string& command) {
  if (!scene.is_free_body() && !scene.declares_only<system::GravityTerm>())
    throw InputError(scene.file + ": lgi " + command +
                     " needs a heavy top (gravity and no other torque term; a spring, drive or dipole has no "
                     "amended potential)");
  HeavyTopBody body;
  body.J = scene.inertia;
  if (const auto& g = scene.declared<system::GravityTerm>())
    body.weight = scene.mass.value_or(0.0) * g->g * scene.center_of_mass.value_or(Vec3::Zero());
  return body;
}

double amended_potential(const HeavyTopBody& body, double l, const Vec3& gamma) {
  return l * l / (2.0 * gamma.dot(body.J * gamma)) + body.weight.dot(gamma);
}

CriticalSet critical_points(const HeavyTopBody& body, double l) {
  CriticalSet out;
  if (l == 0.0 && body.weight.norm() == 0.0) {
    out.constant = true;  // U_0 ≡ 0: every direction is critical
    return out;
  }
  // Circles of critical points need a symmetry: two equal moments with m g χ on the third axis.
  const Eigen::SelfAdjointEigenSolver<Mat3> principal(body.J);
  bool symmetric = false;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const Vec3 a = principal.eigenvectors().col(k);
    if (std::abs(principal.eigenvalues()(i) - principal.eigenvalues()(j)) <= 1e-12 * body.J.norm() &&
        body.weight.cross(a).norm() <= 1e-12 * body.weight.norm())
      symmetric = true;
  }
  for (const auto& e : equilibria_at(body, l).rows) {
    CriticalPoint c;
    c.gamma = e.gamma, c.value = amended_potential(body, l, e.gamma), c.omega = e.omega, c.branch = e.branch;
    c.stability = e.stability, c.nonlinearly_stable = e.nonlinearly_stable;
    // The Hessian of U_ℓ on the tangent plane: P(∇²U − (γ·∇U) I)P (docs/atlas.md §4).
    const Vec3& g = e.gamma;
    const Vec3 Jg = body.J * g;
    const double q = g.dot(Jg), l2 = l * l;
    const Vec3 grad = -l2 / (q * q) * Jg + body.weight;
    const Mat3 hess = -l2 / (q * q) * body.J + 4.0 * l2 / (q * q * q) * Jg * Jg.transpose() - g.dot(grad) * Mat3::Identity();
    const Vec3 t1 = g.unitOrthogonal(), t2 = g.cross(t1);
    Eigen::Matrix<double, 3, 2> T;
    T << t1, t2;
    const Eigen::Vector2d lambda = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(T.transpose() * hess * T).eigenvalues();
    const double scale = hess.norm();
    const double zero = 1e-9 * scale;
    const bool flat = std::abs(lambda(0)) <= zero || std::abs(lambda(1)) <= zero;
    c.circle = flat && symmetric;
    c.degenerate = flat && !symmetric;
    c.index = (lambda(0) < -zero ? 1 : 0) + (lambda(1) < -zero ? 1 : 0);
    out.points.push_back(c);
  }
  return out;
}

double SphereGrid::theta(int i) const { return std::numbers::pi * i / n; }
double SphereGrid::phi(int j) const { return std::numbers::pi * j / n; }
Vec3 SphereGrid::direction(int i, int j) const {
  const double t = theta(i), p = phi(j);
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

SphereGrid potential_grid(const HeavyTopBody& body, double l, int n, const std::function<bool()>& keep_going) {
  SphereGrid g;
  g.n = n;
  g.U.resize(static_cast<std::size_t>(n + 1) * static_cast<std::size_t>(2 * n));
  for (int i = 0; i <= n; ++i) {
    if (keep_going && !keep_going()) return {};
    for (int j = 0; j < 2 * n; ++j) {
      const int column = i == 0 || i == n ? 0 : j;  // a pole: one value for its row
      g.U[static_cast<std::size_t>(i) * static_cast<std::size_t>(2 * n) + static_cast<std::size_t>(j)] =
          amended_potential(body, l, g.direction(i, column));
    }
  }
  return g;
}

std::string component_topology(int boundaries) {
  if (boundaries <= 0) return "RP3";
  if (boundaries == 1) return "S3";
  if (boundaries == 2) return "S1xS2";
  char name[32];  // "#k(S1xS2)" (snprintf: GCC 12 warns -Wrestrict on the string concatenation)
  std::snprintf(name, sizeof name, "#%d(S1xS2)", boundaries - 1);
  return name;
}

std::string energy_surface_topology(std::vector<std::string> names) {
  if (names.empty()) return "empty";
  std::sort(names.begin(), names.end(),
            [](const std::string& a, const std::string& b) { return name_rank(a) < name_rank(b); });
  std::string out;
  for (std::size_t k = 0; k < names.size();) {
    std::size_t e = k;
    while (e < names.size() && names[e] == names[k]) ++e;
    const std::size_t count = e - k;
    if (!out.empty()) out += " + ";
    if (count == 1) out += names[k];
    else out += std::to_string(count) + (names[k] == "S3" || names[k] == "RP3" ? names[k] : "(" + names[k] + ")");
    k = e;
  }
  return out;
}

namespace {
Region region_polled(const SphereGrid& grid, const CriticalSet& critical, double h, const Poll& poll) {
  const Triangulation t = triangulate(grid, poll);
  ComponentSweep sweep(t, entry_order(t, poll), poll);
  sweep.advance_to(h);
  Region r;
  std::map<int, MorseCount> morse;
  r.resolved = critical.constant || morse_counts(t, sweep, critical, h, morse);
  std::map<int, int> id_of;
  std::vector<std::string> names;
  for (const int root : sweep.roots()) {
    RegionComponent c;
    c.id = static_cast<int>(r.components.size());
    c.euler = sweep.euler(root), c.boundaries = 2 - c.euler, c.topology = component_topology(c.boundaries);
    c.area = sweep.area(root), c.u_min = t.value[static_cast<std::size_t>(root)];
    const MorseCount m = morse[root];
    c.minima = m.minima, c.saddles = m.saddles, c.maxima = m.maxima, c.circles = m.circles, c.euler_morse = m.euler;
    c.degenerate = m.degenerate;
    r.degenerate = r.degenerate || m.degenerate > 0;
    if (!critical.constant && m.degenerate == 0 && c.euler_morse != c.euler) r.resolved = false;
    id_of[root] = c.id;
    names.push_back(c.topology);
    r.components.push_back(c);
  }
  r.topology = energy_surface_topology(names);
  r.label.assign(grid.U.size(), -1);
  for (int i = 0; i <= grid.n; ++i) {
    check(poll);
    for (int j = 0; j < grid.meridians(); ++j) {
      const int v = t.vertex(i, j);
      if (sweep.present(v))
        r.label[static_cast<std::size_t>(i) * static_cast<std::size_t>(grid.meridians()) + static_cast<std::size_t>(j)] =
            id_of[sweep.find(v)];
    }
  }
  return r;
}
}  // namespace

Region accessible_region(const SphereGrid& grid, const CriticalSet& critical, double h) {
  return region_polled(grid, critical, h, {});
}

std::optional<Region> accessible_region(const SphereGrid& grid, const CriticalSet& critical, double h,
                                        const std::function<bool()>& keep_going) {
  try {
    return region_polled(grid, critical, h, keep_going);
  } catch (const Stopped&) {
    return std::nullopt;
  }
}

std::vector<RegionSummary> region_summaries(const SphereGrid& grid, const CriticalSet& critical,
                                            const std::vector<double>& energies,
                                            const std::function<bool(std::size_t)>& keep_going) {
  std::size_t done = 0;
  const Poll poll = keep_going ? Poll([&] { return keep_going(done); }) : Poll();
  try {
    const Triangulation t = triangulate(grid, poll);
    ComponentSweep sweep(t, entry_order(t, poll), poll);
    std::vector<std::size_t> order(energies.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return energies[a] < energies[b]; });
    std::vector<RegionSummary> out(energies.size());
    for (const std::size_t k : order) {
      check(poll);
      const double h = energies[k];
      sweep.advance_to(h);
      std::map<int, MorseCount> morse;
      RegionSummary& s = out[k];
      s.resolved = critical.constant || morse_counts(t, sweep, critical, h, morse);
      std::vector<std::string> names;
      for (const int root : sweep.roots()) {
        const int euler = sweep.euler(root);
        names.push_back(component_topology(2 - euler));
        s.euler += euler;
        s.euler_morse += morse[root].euler;
        s.degenerate = s.degenerate || morse[root].degenerate > 0;
        if (!critical.constant && morse[root].degenerate == 0 && morse[root].euler != euler) s.resolved = false;
      }
      s.components = static_cast<int>(names.size());
      s.topology = energy_surface_topology(names);
      ++done;
    }
    return out;
  } catch (const Stopped&) {
    return {};
  }
}

}  // namespace lgi::experiments

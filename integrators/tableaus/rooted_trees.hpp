#pragma once
// Rooted trees up to nine vertices, enumerated at compile time, and the
// Runge–Kutta order conditions they index (Butcher, Numerical Methods for
// Ordinary Differential Equations, 3rd ed. (2016), §3.1–3.3; Hairer,
// Nørsett & Wanner, Solving ODEs I (2nd ed., 1993), §II.2, Theorem 2.13).
//
// A tree τ = [τ_1, …, τ_m] is its root with the subtrees τ_k grafted on. For
// an s-stage tableau (A, c) its elementary weight vector is
//   Φ(•) = 1,   Φ_i(τ) = Π_k (A Φ(τ_k))_i,
// its density γ(•) = 1, γ(τ) = |τ| Π_k γ(τ_k), and weights w give order p iff
//   Σ_i w_i Φ_i(τ) = 1/γ(τ)   for every τ with |τ| ≤ p.
// A continuous extension w(θ) = Σ_k w_k θ^k (dense output) has order q iff
// Σ_i (w_k)_i Φ_i(τ) = δ_{k,|τ|}/γ(τ) for every |τ| ≤ q and every power k
// (HNW I, §II.6, Theorem 6.1: the condition on Σ b_i(θ) Φ_i(τ) = θ^{|τ|}/γ(τ),
// coefficient by coefficient).
//
// Trees are generated order by order as the multisets of smaller trees whose
// orders add up to |τ| − 1 (children listed by non-increasing index, so each
// multiset, i.e. each tree, appears once). The counts 1, 1, 2, 4, 9, 20, 48,
// 115, 286 (OEIS A000081) are checked below.
#include <array>
#include <cstddef>
#include <cstdint>

namespace lgi::tableaus {

/// The largest number of vertices of an enumerated tree.
inline constexpr int max_tree_order = 9;

struct RootedTree {
  int order = 0;        // |τ|, the number of vertices
  double gamma = 1.0;   // γ(τ), the density
  int child_count = 0;  // m
  std::array<std::uint16_t, max_tree_order - 1> children{};  // indices of τ_1..τ_m in the forest
};

/// Every rooted tree with at most max_tree_order vertices, by non-decreasing order.
struct Forest {
  static constexpr std::size_t capacity = 486;  // Σ_{n ≤ 9} A000081(n)
  std::array<RootedTree, capacity> trees{};
  std::size_t count = 0;
};

namespace detail {
/// Appends every tree of order `order` whose children, chosen among the
/// trees with index ≤ max_child, add up to `remaining` vertices besides
/// those already in `partial`.
constexpr void grow(Forest& forest, int order, int remaining, std::size_t max_child, RootedTree& partial) {
  if (remaining == 0) {
    RootedTree tree = partial;
    tree.order = order;
    tree.gamma = order;
    for (int k = 0; k < tree.child_count; ++k)
      tree.gamma *= forest.trees[tree.children[static_cast<std::size_t>(k)]].gamma;
    forest.trees[forest.count++] = tree;
    return;
  }
  for (std::size_t k = max_child + 1; k-- > 0;) {
    const int child_order = forest.trees[k].order;
    if (child_order > remaining) continue;
    partial.children[static_cast<std::size_t>(partial.child_count++)] = static_cast<std::uint16_t>(k);
    grow(forest, order, remaining - child_order, k, partial);
    --partial.child_count;
  }
}

constexpr Forest make_forest() {
  Forest forest;
  forest.trees[0] = RootedTree{};  // •
  forest.trees[0].order = 1;
  forest.count = 1;
  for (int n = 2; n <= max_tree_order; ++n) {
    const std::size_t smaller = forest.count;  // trees of order < n
    RootedTree partial{};
    grow(forest, n, n - 1, smaller - 1, partial);
  }
  return forest;
}
}  // namespace detail

inline constexpr Forest rooted_trees = detail::make_forest();

/// Number of trees with exactly n vertices.
constexpr int trees_of_order(int n) {
  int count = 0;
  for (std::size_t k = 0; k < rooted_trees.count; ++k) count += rooted_trees.trees[k].order == n ? 1 : 0;
  return count;
}

static_assert(rooted_trees.count == Forest::capacity);
static_assert(trees_of_order(1) == 1 && trees_of_order(2) == 1 && trees_of_order(3) == 2 && trees_of_order(4) == 4 &&
              trees_of_order(5) == 9 && trees_of_order(6) == 20 && trees_of_order(7) == 48 &&
              trees_of_order(8) == 115 && trees_of_order(9) == 286);

namespace detail {
constexpr double magnitude(double x) { return x < 0 ? -x : x; }

/// |value − target| ≤ tol · max(scale, |target|), or, for target 0 (a
/// dense-output coefficient), ≤ tol · scale.
constexpr bool agrees(double value, double scale, double target, double tolerance) {
  const double t = magnitude(target);
  return magnitude(value - target) <= tolerance * (scale > t ? scale : t);
}
}  // namespace detail

/// For each of N weight vectors w_r over one tableau, the largest p ≤ max_order
/// such that w_r satisfies the order conditions of every tree with at most p
/// vertices, each taken as
///   Σ_i w_r,i Φ_i(τ) = (|τ| == powers[r] ? 1/γ(τ) : 0),
/// with power 0 meaning "the target is 1/γ(τ) for every tree" (plain weights
/// b). A dense-output coefficient w_k is checked with power = k. Each sum is
/// compared with a relative tolerance whose scale is the same sum in absolute
/// values (which bounds its rounding error). A Φ(τ) is built once for all N
/// vectors (a dense output's D coefficients, or b and b̂ of a pair): it is
/// most of a check's constant evaluation (docs/performance.md §8).
template <std::size_t S, std::size_t N>
constexpr std::array<int, N> orders_of_weights(const std::array<std::array<double, S>, S>& a,
                                               const std::array<std::array<double, S>, N>& w,
                                               const std::array<int, N>& powers, int max_order, double tolerance) {
  // A Φ(τ) and |A| |Φ(τ)| for every tree checked so far.
  struct Stored {
    std::array<double, S> value{}, scale{};
  };
  std::array<Stored, Forest::capacity> a_phi{};
  std::array<int, N> order{};
  order.fill(max_order);
  for (std::size_t k = 0; k < rooted_trees.count; ++k) {
    const RootedTree& tree = rooted_trees.trees[k];
    int highest = 0;  // trees come by non-decreasing order: stop past every vector's
    for (const int o : order) highest = o > highest ? o : highest;
    if (tree.order > highest) break;
    std::array<double, S> phi{}, phi_scale{};
    for (std::size_t i = 0; i < S; ++i) {
      phi[i] = 1.0;
      phi_scale[i] = 1.0;
      for (int m = 0; m < tree.child_count; ++m) {
        phi[i] *= a_phi[tree.children[static_cast<std::size_t>(m)]].value[i];
        phi_scale[i] *= a_phi[tree.children[static_cast<std::size_t>(m)]].scale[i];
      }
    }
    for (std::size_t r = 0; r < N; ++r) {
      if (tree.order > order[r]) continue;  // this vector failed a smaller tree
      double sum = 0.0, scale = 0.0;
      for (std::size_t i = 0; i < S; ++i) {
        sum += w[r][i] * phi[i];
        scale += detail::magnitude(w[r][i]) * phi_scale[i];
      }
      const double target = (powers[r] == 0 || powers[r] == tree.order) ? 1.0 / tree.gamma : 0.0;
      if (!detail::agrees(sum, scale, target, tolerance)) order[r] = tree.order - 1;  // finish no higher tree
    }
    if (tree.order == max_order) continue;  // no bigger tree grafts it
    for (std::size_t i = 0; i < S; ++i) {
      double value = 0.0, bound = 0.0;
      for (std::size_t j = 0; j < S; ++j) {
        if (a[i][j] == 0.0) continue;
        value += a[i][j] * phi[j];
        bound += detail::magnitude(a[i][j]) * phi_scale[j];
      }
      a_phi[k].value[i] = value;
      a_phi[k].scale[i] = bound;
    }
  }
  return order;
}

/// orders_of_weights for one vector w (any indexable of S doubles).
template <std::size_t S, class Weights>
constexpr int order_of_weights(const std::array<std::array<double, S>, S>& a, const Weights& w, int max_order,
                               double tolerance, int power = 0) {
  std::array<std::array<double, S>, 1> rows{};
  for (std::size_t i = 0; i < S; ++i) rows[0][i] = w[i];
  return orders_of_weights(a, rows, std::array<int, 1>{power}, max_order, tolerance)[0];
}

/// The largest relative residual γ(τ)|Σ_i w_i Φ_i(τ) − 1/γ(τ)| over the trees
/// with exactly `order` vertices (order ≤ max_tree_order): how small the
/// weights' error coefficients at that order are (the tests read it for a
/// method's order p + 1, where it sets how soon the error shows its order).
template <std::size_t S, class Weights>
constexpr double largest_relative_residual(const std::array<std::array<double, S>, S>& a, const Weights& w,
                                           int order) {
  struct Stored {
    std::array<double, S> value{};
  };
  std::array<Stored, Forest::capacity> a_phi{};
  double worst = 0.0;
  for (std::size_t k = 0; k < rooted_trees.count; ++k) {
    const RootedTree& tree = rooted_trees.trees[k];
    if (tree.order > order) break;
    std::array<double, S> phi{};
    double sum = 0.0;
    for (std::size_t i = 0; i < S; ++i) {
      phi[i] = 1.0;
      for (int m = 0; m < tree.child_count; ++m) phi[i] *= a_phi[tree.children[static_cast<std::size_t>(m)]].value[i];
      sum += w[i] * phi[i];
    }
    if (tree.order == order) {
      const double r = detail::magnitude(sum * tree.gamma - 1.0);
      worst = r > worst ? r : worst;
      continue;
    }
    for (std::size_t i = 0; i < S; ++i)
      for (std::size_t j = 0; j < S; ++j) a_phi[k].value[i] += a[i][j] * phi[j];
  }
  return worst;
}

}  // namespace lgi::tableaus

// The compile-time order checks of the Runge–Kutta pairs (rooted_trees.hpp,
// embedded_pairs.hpp), evaluated at run time on Verner's 6(5) pair and on
// copies with one coefficient moved: each check must fail where a coefficient
// is wrong, and orders_of_weights, which checks several weight vectors in one
// pass over the trees, must give each vector the order it has alone.
#include <catch2/catch.hpp>
#include <array>
#include <cstddef>

#include "integrators/tableaus/embedded_pairs.hpp"
#include "integrators/tableaus/verner65.hpp"

namespace test_order_checks {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

namespace {
using namespace lgi::tableaus;

// β_3,4 of the interpolant moved by 1e-10: b_i(1) = β_6,i is kept, so only the
// dense output's order conditions see it.
constexpr auto moved_dense = [] {
  auto p = verner65;
  p.dense[3][4] += 1e-10;
  return p;
}();

// b̂_5 and b̂_6 moved by ±1e-10: Σ b̂_i = 1 still holds, and b̂ loses its order 5.
constexpr auto moved_b_hat = [] {
  auto p = verner65;
  p.b_hat[5] += 1e-10;
  p.b_hat[6] -= 1e-10;
  return p;
}();

}  // namespace

TEST_CASE("a pair's order checks hold for Verner's 6(5) and fail where a coefficient moved", "[tableaus]") {
  CHECK(pair_checks_out<verner65>());
  CHECK(dense_output_order<verner65>() == 6);
  CHECK(dense_output_order<moved_dense>() < 6);
  CHECK_FALSE(pair_checks_out<moved_dense>());
  CHECK(dense_output_order<moved_b_hat>() == 6);
  CHECK_FALSE(pair_checks_out<moved_b_hat>());
}

TEST_CASE("orders_of_weights gives each weight vector its own order", "[tableaus]") {
  constexpr double tol = pair_condition_tolerance;
  const std::array<double, 9> zeros{};
  const auto orders = orders_of_weights(verner65.a, std::array{verner65.b, verner65.b_hat, zeros, moved_b_hat.b_hat},
                                        std::array<int, 4>{}, max_checked_order, tol);
  CHECK(orders[0] == 6);
  CHECK(orders[1] == 5);
  CHECK(orders[2] == 0);
  CHECK(orders[3] >= 1);
  CHECK(orders[3] < 5);
  CHECK(orders[3] == order_of_weights(verner65.a, moved_b_hat.b_hat, max_checked_order, tol));

  // The interpolant's coefficients together, against each alone.
  const auto dense = monomial_dense(moved_dense);
  int alone = max_checked_order;
  for (std::size_t k = 1; k < dense.size(); ++k) {
    const int q = order_of_weights(moved_dense.extended.a, dense[k], 7, tol, static_cast<int>(k));
    alone = q < alone ? q : alone;
  }
  CHECK(alone < 6);
  CHECK(dense_output_order<moved_dense>() == alone);
}

}  // namespace test_order_checks

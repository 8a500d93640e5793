// Round-off that does not drift (integrators/core/compensated_sum.hpp,
// integrators/schemes/moser_veselov.hpp): dmv on the book of seed 000 at dt = 0.01
// (dzhanibekov_book_axis2), the energy error after 10⁶ steps (default suite)
// and 10⁸ steps ([slow]). Without compensated updates and the final Newton
// correction the errors were 1.9e-13 and 7.0e-12 (an n^0.84
// drift); with them 7.2e-15 and 5.5e-13, below the bars here. |Π| and the
// spatial momentum, which the Cayley step conserves exactly, stay at the
// 1e-14 level.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <vector>

#include "experiments/analysis/scheme_verification.hpp"
#include "integrators/schemes/moser_veselov_diagonal.hpp"
#include "support/registered_run.hpp"
#include "support/shipped_scene.hpp"

namespace test_round_off {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;

namespace {

struct Errors {
  double energy, momentum_norm;
};

Errors dmv_on_the_book(std::int64_t steps) {
  const system::Scene scene = testing::shipped_scene("dzhanibekov_book_axis2");
  const system::AnyModel model = system::make_model(scene);
  const system::SceneInvariants inv(scene, model);
  experiments::verification::InvariantDrift watch(inv);  // energy, and |Π| as scalars[0]
  const double h = 0.01;
  const auto run = testing::run_registered("dmv", model, scene.initial, static_cast<double>(steps) * h, h, &watch,
                                           steps / 1000);
  REQUIRE(run.stats.ok);
  std::cout << "dmv on the book, " << steps << " steps at dt = 0.01: energy error " << watch.energy << ", |Pi| error "
            << watch.scalars[0] << '\n';
  return {watch.energy, watch.scalars[0]};
}

}  // namespace

TEST_CASE("dmv: the energy error of 1e6 steps stays at round-off", "[round-off]") {
  const Errors w = dmv_on_the_book(1000000);
  CHECK(w.energy <= 2e-14);
  CHECK(w.momentum_norm <= 2e-14);
}

TEST_CASE("dmv: the energy error of 1e8 steps stays below 2e-12", "[round-off][slow]") {
  const Errors w = dmv_on_the_book(100000000);
  CHECK(w.energy <= 2e-12);
  CHECK(w.momentum_norm <= 1e-13);
}

namespace {

/// The largest relative energy error so far, read at the given step counts.
class EnergyErrorAt final : public integrators::Observer {
 public:
  EnergyErrorAt(const system::SceneInvariants& inv, const system::State& x0, std::vector<std::int64_t> at)
      : inv_(inv), H0_(inv.energy(x0)), at_(std::move(at)), max_at_(at_.size(), 0.0) {}
  void observe(std::int64_t step, double, const system::State& s) override {
    max_ = std::max(max_, std::abs(inv_.energy(s) - H0_) / std::abs(H0_));
    for (std::size_t k = 0; k < at_.size(); ++k)
      if (step == at_[k]) max_at_[k] = max_;
  }
  const std::vector<double>& values() const { return max_at_; }

 private:
  const system::SceneInvariants& inv_;
  double H0_, max_ = 0.0;
  std::vector<std::int64_t> at_;
  std::vector<double> max_at_;
};

/// The rms over `members` books (ω0 of the book plus k·(3e-4, −2e-4, 1e-4)·|ω0|,
/// k = 0..members−1) of the largest energy error up to each of `at` steps,
/// and the slope of log(rms) over log(n) between the first and the last.
double growth_exponent(int members, const std::vector<std::int64_t>& at) {
  const system::Scene scene = testing::shipped_scene("dzhanibekov_book_axis2");
  const system::AnyModel model = system::make_model(scene);
  const system::SceneInvariants inv(scene, model);
  std::vector<double> sum2(at.size(), 0.0);
  for (int k = 0; k < members; ++k) {
    system::State x0 = scene.initial;
    x0.Pi += static_cast<double>(k) * x0.Pi.norm() * lie::Vec3(3e-4, -2e-4, 1e-4);
    EnergyErrorAt watch(inv, x0, at);
    const auto run = testing::run_registered("dmv", model, x0, static_cast<double>(at.back()) * 0.01, 0.01, &watch,
                                             at.front() / 100);
    REQUIRE(run.stats.ok);
    for (std::size_t j = 0; j < at.size(); ++j) sum2[j] += watch.values()[j] * watch.values()[j];
  }
  for (std::size_t j = 0; j < at.size(); ++j)
    std::cout << "dmv, " << members << " books, " << at[j] << " steps: rms energy error "
              << std::sqrt(sum2[j] / static_cast<double>(members)) << '\n';
  return 0.5 * std::log(sum2.back() / sum2.front()) / std::log(static_cast<double>(at.back()) / static_cast<double>(at.front()));
}

}  // namespace

// A drift grows like n (exponent 1; with the biased residual the fit from
// 10⁶ to 10⁸ steps gave 0.95 on such an ensemble), a random walk like √n
// (exponent ½). Over 10⁶–10⁷ steps the bounded O(h²) energy oscillation still
// hides the difference (0.69 biased, 0.59 unbiased on 4 books), so the default
// suite checks the bias itself (above) and this the growth.
TEST_CASE("dmv: the energy error grows like sqrt(n) from 10^6 to 10^8 steps (8 books)", "[round-off][slow]") {
  const double p = growth_exponent(8, {1000000, 10000000, 100000000});
  std::cout << "fitted exponent " << p << '\n';
  CHECK(p < 0.65);
  CHECK(p > 0.3);
}

namespace {

/// Along `steps` dmv steps on the book, the energy change that the solved f's
/// error alone makes in each step, ΔE = E(Fᵀ Π; f) − E(Fᵀ Π; f*), against f*
/// solved in long double (Newton on ψ of moser_veselov_diagonal.hpp from f) for
/// the body the step solves for, the moments 1/μ (μ = 1/I rounded, DiagonalMoments),
/// whose energy E is;
/// returns z = Σ ΔE / √(Σ ΔE²). Unbiased errors give |z| of order 1; a bias of
/// one sign grows z like √n, and it is what drifts the energy linearly.
double solve_bias_z(std::int64_t steps) {
  using LD = long double;
  const system::Scene scene = testing::shipped_scene("dzhanibekov_book_axis2");
  const lie::Vec3 moments = scene.inertia.diagonal();
  const integrators::moser_veselov::DiagonalMoments m(moments, moments.cwiseInverse());
  const LD I_of[3] = {1.0L / static_cast<LD>(m.mu.x()), 1.0L / static_cast<LD>(m.mu.y()), 1.0L / static_cast<LD>(m.mu.z())};
  auto I = [&](int i) { return I_of[i]; };
  const double h = 0.01;
  system::State s = scene.initial;
  integrators::moser_veselov::Carry carry;
  auto energy_after = [&](const LD (&f)[3]) {  // E(Fᵀ Π) with F = cay(2f), in long double
    const LD x = f[0], y = f[1], z = f[2], c = 2.0L / (1.0L + (x * x + y * y + z * z));
    const LD N[3][3] = {{-(y * y + z * z), x * y - z, x * z + y},
                        {x * y + z, -(x * x + z * z), y * z - x},
                        {x * z - y, y * z + x, -(x * x + y * y)}};
    LD e = 0.0L;
    for (int i = 0; i < 3; ++i) {
      LD p = s.Pi(i);
      for (int k = 0; k < 3; ++k) p += c * N[k][i] * static_cast<LD>(s.Pi(k));
      e += p * p / (2.0L * I(i));
    }
    return e;
  };
  LD sum = 0.0L, sum2 = 0.0L;
  std::int64_t unconverged = 0;
  for (std::int64_t n = 0; n < steps; ++n) {
    integrators::moser_veselov::DiagonalSolution solved_now;
    unconverged += integrators::moser_veselov::solve_cayley_parameter_diagonal(m, h, s.Pi, solved_now).converged ? 0 : 1;
    const lie::Vec3 f = solved_now.f;
    LD g[3] = {f.x(), f.y(), f.z()}, r[3];
    const LD a[3] = {static_cast<LD>(h) * s.Pi.x(), static_cast<LD>(h) * s.Pi.y(), static_cast<LD>(h) * s.Pi.z()};
    for (int it = 0; it < 3; ++it) {  // Newton on ψ(f) = 2Jf + 2 f × Jf − (1 + |f|²) a, Jacobian by Cramer
      const LD w[3] = {I(0) * g[0], I(1) * g[1], I(2) * g[2]}, al = 1.0L + g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
      for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        r[i] = 2.0L * (w[i] + g[j] * w[k] - g[k] * w[j]) - al * a[i];
      }
      LD D[3][3];
      for (int i = 0; i < 3; ++i)
        for (int c = 0; c < 3; ++c) {
          const int j = (i + 1) % 3, k = (i + 2) % 3;
          LD d = (c == i ? 2.0L * I(i) : 0.0L) - 2.0L * a[i] * g[c];
          if (c == j) d += 2.0L * (-w[k] + g[k] * I(j));
          if (c == k) d += 2.0L * (w[j] - g[j] * I(k));
          D[i][c] = d;
        }
      const LD det = D[0][0] * (D[1][1] * D[2][2] - D[1][2] * D[2][1]) -
                     D[0][1] * (D[1][0] * D[2][2] - D[1][2] * D[2][0]) + D[0][2] * (D[1][0] * D[2][1] - D[1][1] * D[2][0]);
      LD x[3];
      for (int c = 0; c < 3; ++c) {
        LD M[3][3];
        for (int i = 0; i < 3; ++i)
          for (int q = 0; q < 3; ++q) M[i][q] = q == c ? r[i] : D[i][q];
        x[c] = (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0])) / det;
      }
      for (int c = 0; c < 3; ++c) g[c] -= x[c];
    }
    const LD solved[3] = {f.x(), f.y(), f.z()};
    const LD dE = energy_after(solved) - energy_after(g);
    sum += dE, sum2 += dE * dE;
    integrators::moser_veselov::apply_cayley_step(f, s, carry);
  }
  CHECK(unconverged == 0);
  const double z = static_cast<double>(sum / std::sqrt(sum2));
  std::cout << "dmv on the book, " << steps << " steps: bias of the solve's energy change z = " << z << '\n';
  return z;
}

}  // namespace

// With ψ rounded as 2(w + f × w) − α a, z was +4.17 over 4·10⁶ steps and grew
// like √n (+6.6 expected over 10⁷); with the accurate residual it is −2.58 at
// 4·10⁶ and −1.80 at 10⁷ steps: no growth, no bias.
TEST_CASE("dmv: the implicit solve leaves no bias that would drift the energy (1e7 steps)", "[round-off]") {
  CHECK(std::abs(solve_bias_z(10000000)) < 4.0);
}

}  // namespace test_round_off

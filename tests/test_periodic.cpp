// Periodic orbits of the Euler–Poisson flow (experiments/analysis/periodic/,
// experiments/PERIODIC.md):
//  - the sixth-order midpoint composition keeps H, Π·Γ and |Γ|² to round-off;
//  - on Richter's general top at ℓ = 2.2 and 3, every Lyapunov family of every
//    linearly stable equilibrium starts with a period within 1e-6 of 2π/ω and
//    an energy within 1e-6 of the equilibrium's; every orbit has a residual
//    ≤ 1e-10, a product of multipliers within 1e-8 of 1, and four multipliers
//    within 1e-8 of 1;
//  - a period doubling on a family at ℓ = 2.2: located to |tr P + 2| ≤ 1e-8,
//    confirmed by an independent monodromy (Boost.Odeint's Dormand–Prince on
//    variational equations written out here) with a multiplier within 1e-6 of
//    −1, and the doubled family branching off it with period ≈ 2T, a new
//    orbit (off the parent by ε along the eigenvector of −1, not closed after
//    half its period);
//  - a fold on a family at ℓ = 3: h turns there, |tr P − 2| ≤ 1e-8, and the
//    independent monodromy's trace is 6 (= 4 trivial + tr P) to 1e-6;
//  - one orbit re-integrated for one period by rkmk4 on SO(3) × ℝ³ (another
//    scheme, another state space) returns to its point to 1e-8;
//  - the general top's orbits are not reported degenerate; on a Lagrange top the
//    carrousels' families are, with periods integer multiples of T_theta to 1e-9.
// odeint copies its steppers' scratch arrays before their first use, which
// GCC reports (-Wuninitialized) once inlined; the copies are overwritten before
// they are read (as in support/reference_solution.hpp: whichever file of a unity
// batch includes odeint first decides, so every include of it is wrapped).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/numeric/odeint.hpp>
#pragma GCC diagnostic pop
#include <catch2/catch.hpp>
#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <numbers>

#include "experiments/analysis/actions.hpp"
#include "experiments/analysis/periodic/lyapunov_families.hpp"
#include "experiments/io/gamma_attitude.hpp"
#include "integrators/registry/registry.hpp"
#include "support/heavy_top_body.hpp"
#include "support/shipped_scene.hpp"

namespace test_periodic {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

using namespace lgi;
using testing::body_of;
using experiments::HeavyTopBody;
using experiments::Vec6;

namespace {

struct EndRecorder final : integrators::Observer {
  system::State last;
  void observe(std::int64_t, double, const system::State& x) override { last = x; }
};

/// (Π, Γ) after one period of rkmk4 on SO(3) × ℝ³ from x0.
Vec6 rerun(system::Scene scene, const Vec6& x0, double T, double dt) {
  scene.initial.R = experiments::attitude_from_gamma(lie::Vec3(x0.tail<3>()).normalized());
  scene.initial.Pi = x0.head<3>();
  const system::AnyModel model = system::make_model(scene);
  EndRecorder rec;
  const auto steps = static_cast<std::int64_t>(std::ceil(T / dt));
  integrators::RunConfig cfg{0.0, T, T / static_cast<double>(steps), 0.0, steps};
  system::State x = scene.initial;
  REQUIRE(integrators::find_scheme("rkmk4")->run(model, x, cfg, rec).ok);
  Vec6 out;
  out << rec.last.Pi, rec.last.R.transpose() * lie::Vec3::UnitZ();
  return out;
}

/// The monodromy of the Euler–Poisson flow over [0, T] from x0 by Dormand–Prince
/// 5(4) at tolerance 1e-12 on the variational equations, written out here:
/// δΠ' = δΠ × Ω + Π × J⁻¹δΠ + δΓ × w,  δΓ' = δΓ × Ω + Γ × J⁻¹δΠ.
experiments::Mat6 independent_monodromy(const HeavyTopBody& b, const Vec6& x0, double T) {
  using Y = std::array<double, 42>;
  const Eigen::Matrix3d Jinv = b.J.inverse();
  const auto rhs = [&](const Y& y, Y& dy, double) {
    const Eigen::Map<const Eigen::Matrix<double, 6, 7>> Z(y.data());
    Eigen::Map<Eigen::Matrix<double, 6, 7>> D(dy.data());
    const lie::Vec3 Pi = Z.col(0).head<3>(), G = Z.col(0).tail<3>(), Om = Jinv * Pi;
    D.col(0) << Pi.cross(Om) + G.cross(b.weight), G.cross(Om);
    for (int k = 1; k < 7; ++k) {
      const lie::Vec3 dP = Z.col(k).head<3>(), dG = Z.col(k).tail<3>(), dOm = Jinv * dP;
      D.col(k) << dP.cross(Om) + Pi.cross(dOm) + dG.cross(b.weight), dG.cross(Om) + G.cross(dOm);
    }
  };
  Y y{};
  Eigen::Map<Eigen::Matrix<double, 6, 7>> Z(y.data());
  Z.col(0) = x0;
  Z.rightCols<6>().setIdentity();
  namespace ode = boost::numeric::odeint;
  ode::integrate_adaptive(ode::make_controlled(1e-12, 1e-12, ode::runge_kutta_dopri5<Y>()), rhs, y, 0.0, T, 1e-3);
  return Z.rightCols<6>();
}

}  // namespace

TEST_CASE("the midpoint composition keeps H, C and |Gamma|^2", "[periodic]") {
  const HeavyTopBody body = body_of(testing::shipped_scene("general_top_richter"));
  Vec6 x;
  x << 0.3, -1.1, 2.0, 0.6, 0.0, 0.8;
  const auto before = experiments::euler_poisson_invariants(body, x).value;
  const auto shot = experiments::shoot(body, x, 7.3, 1e-2);
  REQUIRE(shot.ok);
  const auto after = experiments::euler_poisson_invariants(body, shot.end).value;
  CHECK((after - before).cwiseAbs().maxCoeff() <= 1e-13);
  CHECK(std::abs(shot.monodromy.determinant() - 1.0) <= 1e-12);  // a divergence-free field
}

TEST_CASE("Lyapunov families of a general top: periods, residuals, multipliers", "[periodic]") {
  const auto scene = testing::shipped_scene("general_top_richter");
  const HeavyTopBody body = body_of(scene);
  experiments::FamilySettings s;
  s.steps = 1;
  s.h_step = 0.02;
  bool rerun_done = false;
  for (const double l : {2.2, 3.0}) {
    std::vector<std::string> failures;
    const auto rows = experiments::lyapunov_families(body, l, s, failures);
    CHECK(failures.empty());
    const auto eqs = experiments::equilibria_at(body, l).rows;
    int stable_modes = 0;
    for (const auto& e : eqs)
      if (e.stability == experiments::EquilibriumStability::stable)
        stable_modes += static_cast<int>(experiments::equilibrium_frequencies(e).size());
    int firsts = 0;
    for (const auto& r : rows) {
      INFO("l = " << l << " family " << r.family << " index " << r.index << " T = " << r.orbit.period);
      CHECK(r.orbit.residual <= 1e-10);
      CHECK(r.orbit.trivial_deviation <= 1e-8);
      CHECK(r.orbit.invariance_defect <= 1e-8);
      CHECK(r.orbit.product_deviation <= 1e-8);
      CHECK_FALSE(r.orbit.degenerate);
      if (r.index != 0) continue;
      ++firsts;
      CHECK(std::abs(r.orbit.period - 2.0 * std::numbers::pi / r.omega) <= 1e-6);
      CHECK(std::abs(r.orbit.h - eqs[static_cast<std::size_t>(r.equilibrium)].h) <= 1e-6);
    }
    CHECK(firsts == stable_modes);
    CHECK(stable_modes >= 2);
    if (!rerun_done && !rows.empty()) {
      const auto& o = rows.back().orbit;
      CHECK((rerun(scene, o.x0, o.period, 2e-4) - o.x0).norm() <= 1e-8);
      rerun_done = true;
    }
  }
}

TEST_CASE("Lagrange top: the carrousels' families are degenerate, periods multiples of T_theta", "[periodic]") {
  const auto scene = testing::shipped_scene("lagrange_top_cigar");
  const HeavyTopBody body = body_of(scene);
  const auto lagrange = experiments::lagrange_body(body);
  REQUIRE(lagrange);
  experiments::FamilySettings s;
  s.steps = 1;
  s.h_step = 0.02;
  int degenerate = 0;
  std::vector<std::string> failures;
  for (const auto& r : experiments::lyapunov_families(body, 3.0, s, failures)) {
    CHECK(r.orbit.residual <= 1e-10);
    if (!r.orbit.degenerate) continue;
    ++degenerate;
    const auto torus = experiments::lagrange_actions(*lagrange, 3.0, r.orbit.x0(2), r.orbit.h);
    REQUIRE(torus);
    const double ratio = r.orbit.period / torus->period;
    INFO("family " << r.family << " T = " << r.orbit.period << " T_theta = " << torus->period);
    CHECK(std::abs(ratio - std::round(ratio)) * torus->period <= 1e-9);
    CHECK(std::round(ratio) >= 1.0);
  }
  CHECK(degenerate >= 2);
}

TEST_CASE("A period doubling on a family of Richter's top, and the doubled family", "[periodic]") {
  const HeavyTopBody body = body_of(testing::shipped_scene("general_top_richter"));
  // A point of the ℓ = 2.2 family of period ≈ 4.06 (the faster mode of the
  // hanging equilibrium), from `lgi periodic --l 2.2 --from-equilibria`.
  Vec6 x;
  x << -0.5440143623441437, -0.6150665918126653, -2.0653514662689068, -0.33283680104325525, -0.37020048866337674,
      -0.8672780765503418;
  experiments::FamilySettings s;
  s.steps = 3;
  s.h_step = 0.02;
  s.switch_amplitude = 2e-4;
  const double h = experiments::euler_poisson_invariants(body, x).value(0);
  std::vector<std::string> failures;
  const auto rows = experiments::continue_family(body, x, 4.061522325732049, h, 2.2, 1.0, 0, s, failures);
  const experiments::FamilyOrbit* pd = nullptr;
  for (const auto& r : rows) {
    INFO("family " << r.family << " index " << r.index << " h " << r.orbit.h << " event " << r.event);
    CHECK(r.orbit.residual <= 1e-10);
    CHECK(r.orbit.trivial_deviation <= 1e-8);
    CHECK(r.orbit.product_deviation <= 1e-8);
    if (r.family == 0 && r.event == "period_doubling") pd = &r;
  }
  REQUIRE(pd != nullptr);
  CHECK(std::abs(pd->orbit.reduced_trace + 2.0) <= 1e-8);
  CHECK(pd->orbit.h > 0.6930);
  CHECK(pd->orbit.h < 0.6940);
  // Independently: a multiplier of the Dormand–Prince monodromy at −1.
  const Eigen::EigenSolver<experiments::Mat6> es(independent_monodromy(body, pd->orbit.x0, pd->orbit.period), false);
  double nearest = INFINITY;
  for (int k = 0; k < 6; ++k) nearest = std::min(nearest, std::abs(es.eigenvalues()(k) + 1.0));
  CHECK(nearest <= 1e-6);
  CHECK(std::abs(independent_monodromy(body, pd->orbit.x0, pd->orbit.period).trace() - 2.0) <= 1e-6);
  // The doubled family leaves it with period ≈ 2T, its first two orbits (at
  // amplitudes ε and 2ε along the eigenvector of −1) at h − h_pd ∝ ε²: ratio 4.
  std::vector<experiments::PeriodicOrbit> doubled;
  for (const auto& r : rows)
    if (r.parent == 0) doubled.push_back(r.orbit);
  REQUIRE(doubled.size() >= 2);
  INFO("T_pd " << pd->orbit.period << " h_pd " << pd->orbit.h << " first doubled (" << doubled[0].h << ", "
               << doubled[0].period << "), second (" << doubled[1].h << ", " << doubled[1].period << ")");
  CHECK(std::abs(doubled[0].period - 2.0 * pd->orbit.period) <= 0.05);
  const double dh1 = doubled[0].h - pd->orbit.h, dh2 = doubled[1].h - pd->orbit.h;
  CHECK(std::abs(dh1) <= 1e-3);
  CHECK(dh1 * dh2 > 0.0);
  CHECK(std::abs(dh2 / dh1 - 4.0) <= 0.5);
  // A genuine new orbit, not the parent run twice round: its point is off the
  // parent's by ε = 2e-4 |x_pd| along the eigenvector of −1 (the corrector's
  // condition, checked here from the orbits), and half its period does not close it.
  const Eigen::Matrix2d A = pd->orbit.reduced_monodromy + Eigen::Matrix2d::Identity();
  const Vec6 v = (pd->orbit.section_basis * A.col(A.col(0).norm() >= A.col(1).norm() ? 0 : 1)).normalized();
  const double eps = 2e-4 * pd->orbit.x0.norm();
  const Vec6 off = doubled[0].x0 - pd->orbit.x0;
  INFO("offset along v " << off.dot(v) << ", across " << (off - off.dot(v) * v).norm() << ", eps " << eps);
  CHECK(std::abs(std::abs(off.dot(v)) - eps) <= 0.2 * eps);
  const auto half = experiments::shoot(body, doubled[0].x0, 0.5 * doubled[0].period, 2e-3);
  CHECK((half.end - doubled[0].x0).norm() >= 0.5 * eps);
  CHECK(doubled[0].residual <= 1e-10);
}

TEST_CASE("A fold on a family of Richter's top at l = 3", "[periodic]") {
  const HeavyTopBody body = body_of(testing::shipped_scene("general_top_richter"));
  // A point of the ℓ = 3 family from the equilibrium at h = 5.3197 (period
  // 4.056), on its way down in h, from `lgi periodic --l 3 --from-equilibria`.
  Vec6 x;
  x << 2.818457906841236, 0.7805006052769844, -0.7311888712198521, 0.8999516154419804, 0.2838829693001365,
      -0.3309041396004405;
  experiments::FamilySettings s;
  s.steps = 4;
  s.h_step = 0.06;
  const double h = experiments::euler_poisson_invariants(body, x).value(0);
  std::vector<std::string> failures;
  const auto rows = experiments::continue_family(body, x, 4.3128228985108725, h, 3.0, -1.0, 0, s, failures);
  std::size_t fold = rows.size();
  for (std::size_t k = 0; k < rows.size(); ++k) {
    CHECK(rows[k].orbit.residual <= 1e-10);
    CHECK(rows[k].orbit.trivial_deviation <= 1e-8);
    if (rows[k].event == "fold") fold = k;
  }
  REQUIRE(fold < rows.size());
  REQUIRE(fold > 0);
  REQUIRE(fold + 1 < rows.size());
  const auto& f = rows[fold].orbit;
  INFO("fold at h = " << f.h << ", T = " << f.period);
  CHECK(std::abs(f.reduced_trace - 2.0) <= 1e-8);
  CHECK(f.h < rows[fold - 1].orbit.h);
  CHECK(f.h < rows[fold + 1].orbit.h);
  CHECK(std::abs(f.h - 4.918819764955638) <= 1e-6);  // where the 20-step family of `lgi periodic` places it
  CHECK(std::abs(independent_monodromy(body, f.x0, f.period).trace() - 6.0) <= 1e-6);
}

}  // namespace test_periodic

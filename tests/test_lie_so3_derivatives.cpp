// Property tests for the derivatives of lie/so3.hpp (dexp, dexp^-1, dcay, Ad,
// ad), the distances of lie/quaternion.hpp and the product state of
// lie/product_state.hpp, on the deterministic samples of
// support/so3_samples.hpp.
//
// Independent references: central differences, and RK4 on Ṙ = R Ω̂ in ℝ⁹,
// which knows nothing of exp/log.
//
// Set LGI_TEST_REPORT=1 to print the worst error observed for each property.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "integrators/schemes/rkmk_chart.hpp"
#include "lie/product_state.hpp"
#include "lie/quaternion.hpp"
#include "lie/so3.hpp"
#include "support/worst_error.hpp"
#include "support/so3_samples.hpp"
#include "support/rk4.hpp"

namespace test_lie_so3_derivatives {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

namespace {

using lgi::lie::Mat3;
using lgi::lie::Vec3;
using Quat = Eigen::Quaterniond;

constexpr double pi = std::numbers::pi;

using namespace lgi::testing;

}  // namespace

using namespace lgi::lie;

// ===========================================================================

TEST_CASE("dexp · dexp^-1 = I (body, space, Cayley); vector forms equal matrix forms", "[lie][so3]") {
  Worst w_body("dexp_body * dexpinv_body_matrix - I (max entry)");
  Worst w_space("dexp_space * dexpinv_space_matrix - I (max entry)");
  Worst w_vec("dexpinv_{body,space}(xi,w) - matrix * w / (|w| max(1,|M|))");
  Worst w_ls("dexp_space - exp(xi) dexp_body (max entry)");
  Worst w_cay("dcay_body * dcayinv_body_matrix - I (max entry)");
  Worst w_cayv("dcayinv_body(xi,w) - matrix*w, dcay_space*dcayinv_space(xi,w) - w");
  Worst w_cls("dcay_space - cay(xi) dcay_body (max entry)");
  auto all = samples();
  for (double th : {4.0, 6.0}) all.push_back({th, 3, th * axes()[3]});
  for (const Sample& s : all) {
    INFO(describe(s));
    const Mat3 I = Mat3::Identity();
    CHECK(w_body(maxabs(Mat3(dexp_body(s.xi) * dexpinv_body_matrix(s.xi) - I)), describe(s)) <= 2e-15);
    CHECK(w_body(maxabs(Mat3(dexpinv_body_matrix(s.xi) * dexp_body(s.xi) - I)), describe(s)) <= 2e-15);
    CHECK(w_space(maxabs(Mat3(dexp_space(s.xi) * dexpinv_space_matrix(s.xi) - I)), describe(s)) <= 2e-15);
    // Left and right trivialisations differ by Ad_exp(ξ) = exp(ξ): d/dt exp = exp (J_r ξ̇)^ = (exp J_r ξ̇)^ exp.
    CHECK(w_ls(maxabs(Mat3(dexp_space(s.xi) - exp_so3(s.xi) * dexp_body(s.xi))), describe(s)) <= 2e-15);
    for (const Vec3& w : {kEta, kEta2}) {
      // Relative to |dexp⁻¹| |w|: beyond π the ξ̂² term of dexp⁻¹ grows (|c(6)| θ² ≈ 22).
      const double scale = w.norm() * std::max(1.0, maxabs(dexpinv_body_matrix(s.xi)));
      CHECK(w_vec((dexpinv_body(s.xi, w) - dexpinv_body_matrix(s.xi) * w).norm() / scale, describe(s)) <= 2e-15);
      CHECK(w_vec((dexpinv_space(s.xi, w) - dexpinv_space_matrix(s.xi) * w).norm() / scale, describe(s)) <= 2e-15);
      CHECK(w_cayv((dcayinv_body(s.xi, w) - dcayinv_body_matrix(s.xi) * w).norm() / w.norm(), describe(s)) <=
            2e-15);
      CHECK(w_cayv((dcay_space(s.xi) * dcayinv_space(s.xi, w) - w).norm() / w.norm(), describe(s)) <= 2e-15);
    }
    CHECK(w_cay(maxabs(Mat3(dcay_body(s.xi) * dcayinv_body_matrix(s.xi) - I)), describe(s)) <= 2e-15);
    CHECK(w_cls(maxabs(Mat3(dcay_space(s.xi) - cay(s.xi) * dcay_body(s.xi))), describe(s)) <= 2e-15);
  }
}

TEST_CASE("the RKMK charts' plain-number kernels are lie/so3.hpp's maps", "[lie][so3][rkmk]") {
  // integrators/schemes/rkmk_chart.hpp: R φ(ŵ) and dφ⁻¹_body(w) Ω of the exponential and
  // Cayley coordinates, against exp_so3 / dexpinv_body and cay / dcayinv_body
  // (themselves checked against central differences below).
  namespace it = lgi::integrators;
  Worst w_map("R phi(w) - R map(w) (max entry)");
  Worst w_inv("dphiinv(w) Omega - reference / |Omega|");
  const Mat3 R = exp_so3(Vec3(0.3, -1.1, 0.7));
  for (const Sample& s : samples()) {
    if (s.theta >= 3.0) continue;  // RKMK steps stay far below π
    INFO(describe(s));
    const double* w = s.xi.data();
    const auto me = it::ExponentialChart::coefficients(s.xi.squaredNorm());
    const auto mc = it::CayleyChart::coefficients(s.xi.squaredNorm());
    CHECK(w_map(maxabs(Mat3(it::times_map<it::ExponentialChart>(R, w) - R * exp_so3(s.xi))), describe(s)) <= 2e-15);
    CHECK(w_map(maxabs(Mat3(it::times_map<it::CayleyChart>(R, w) - R * cay(s.xi))), describe(s)) <= 2e-15);
    for (const Vec3& omega : {kEta, kEta2}) {
      Vec3 out;
      it::ExponentialChart::inverse_differential(w, omega, me, out.data());
      CHECK(w_inv((out - dexpinv_body(s.xi, omega)).norm() / omega.norm(), describe(s)) <= 4e-15);
      it::CayleyChart::inverse_differential(w, omega, mc, out.data());
      CHECK(w_inv((out - dcayinv_body(s.xi, omega)).norm() / omega.norm(), describe(s)) <= 4e-15);
    }
  }
}

TEST_CASE("dexp, dexp^-1 and dcay against central differences (body and space signs)", "[lie][so3]") {
  // Central difference: truncation ~h²/6 |R'''|, round-off ~ε/h; h = 1e-5 gives ~1e-11 for both.
  const double h = 1e-5;
  const double tol = 1e-8;
  Worst w_eb("exp body:  vee(R^T dR) - dexp_body(xi) eta");
  Worst w_es("exp space: vee(dR R^T) - dexp_space(xi) eta");
  Worst w_ei("exp body:  vee(R^T dR) along dexpinv_body(xi,w) - w");
  Worst w_eis("exp space: vee(dR R^T) along dexpinv_space(xi,w) - w");
  Worst w_cb("cay body:  vee(C^T dC) - dcay_body(xi) eta");
  Worst w_cs("cay space: vee(dC C^T) - dcay_space(xi) eta");
  Worst w_ci("cay body:  vee(C^T dC) along dcayinv_body(xi,w) - w");
  Worst w_skew("skew part residual of R^T dR (exp and cay)");
  Worst w_teeth("[teeth] |body - space| where xi x eta != 0 (must be large)");
  auto diff = [h](const std::function<Mat3(const Vec3&)>& f, const Vec3& xi, const Vec3& eta) -> Mat3 {
    return (f(xi + h * eta) - f(xi - h * eta)) / (2.0 * h);
  };
  const std::function<Mat3(const Vec3&)> fexp = [](const Vec3& x) { return exp_so3(x); };
  const std::function<Mat3(const Vec3&)> fcay = [](const Vec3& x) { return cay(x); };
  for (const Sample& s : samples()) {
    const Vec3 n = axes()[static_cast<std::size_t>(s.axis)];
    for (const Vec3& eta : {kEta, kEta2, n}) {
      INFO(describe(s) << ", eta = (" << eta.transpose() << ")");
      const std::string where = describe(s);
      const Mat3 R = exp_so3(s.xi), C = cay(s.xi);
      const Mat3 dR = diff(fexp, s.xi, eta), dC = diff(fcay, s.xi, eta);
      const Mat3 body = R.transpose() * dR, space = dR * R.transpose();
      CHECK(w_skew(maxabs(Mat3(body + body.transpose())), where) <= tol);
      CHECK(w_eb((vee(body) - dexp_body(s.xi) * eta).norm(), where) <= tol);
      CHECK(w_es((vee(space) - dexp_space(s.xi) * eta).norm(), where) <= tol);
      const Mat3 cbody = C.transpose() * dC, cspace = dC * C.transpose();
      CHECK(w_skew(maxabs(Mat3(cbody + cbody.transpose())), where) <= tol);
      CHECK(w_cb((vee(cbody) - dcay_body(s.xi) * eta).norm(), where) <= tol);
      CHECK(w_cs((vee(cspace) - dcay_space(s.xi) * eta).norm(), where) <= tol);
      // The inverses: moving ξ along dexpinv(ξ, w) gives velocity w.
      const Vec3& w = eta;
      CHECK(w_ei((vee(Mat3(R.transpose() * diff(fexp, s.xi, dexpinv_body(s.xi, w)))) - w).norm(), where) <= tol);
      CHECK(w_eis((vee(Mat3(diff(fexp, s.xi, dexpinv_space(s.xi, w)) * R.transpose())) - w).norm(), where) <= tol);
      CHECK(w_ci((vee(Mat3(C.transpose() * diff(fcay, s.xi, dcayinv_body(s.xi, w)))) - w).norm(), where) <= tol);
      if (s.theta >= 1.0 && s.xi.cross(eta).norm() > 0.1) {
        // Here the body and space forms differ by O(1): the checks above do discriminate the sign.
        CHECK(w_teeth((dexp_body(s.xi) * eta - dexp_space(s.xi) * eta).norm(), where) > 0.05);
        CHECK((dcay_body(s.xi) * eta - dcay_space(s.xi) * eta).norm() > 0.05);
      }
    }
  }
}

TEST_CASE("ξ̇ = dexpinv(ξ, Ω(t)) reproduces Ṙ = R Ω̂(t) (guards the ½ sign)", "[lie][so3]") {
  const double T = 1.0;
  const int n = 1000;  // RK4, h = 1e-3: global errors ~1e-12
  const std::vector<Vec3> starts = {Vec3::Zero(), Vec3(0.3, -0.2, 0.1), Vec3(-1.0, 0.8, 1.5)};
  Worst w_body("|exp(xi(T)) - R(T)|, body, vs RK4 in R^9");
  Worst w_poe("|exp(xi(T)) - R(T)|, body, vs product of midpoint exponentials");
  Worst w_space("|exp(xi(T)) - R(T)|, space (Rdot = w^ R)");
  Worst w_cay("|cay(xi(T)) - R(T)|, body, xi' = dcayinv_body");
  Worst w_teeth("[teeth] error with the space form in a body ODE (must be large)");
  for (const Vec3& xi0 : starts) {
    INFO("xi0 = (" << xi0.transpose() << ")");
    const std::string where = "xi0 = (" + std::to_string(xi0.x()) + ", " + std::to_string(xi0.y()) + ", " +
                              std::to_string(xi0.z()) + ")";
    const Mat3 R0 = exp_so3(xi0);
    const Mat3 Rbody = body_attitude_rk4(R0, T, n);
    const Mat3 Rspace = rk4<Mat3>([](double t, const Mat3& R) { return Mat3(hat(omega_of_t(t)) * R); }, R0, T, n);
    REQUIRE(orthogonality_error(Rbody) < 1e-10);

    const Vec3 xb = rk4<Vec3>([](double t, const Vec3& x) { return dexpinv_body(x, omega_of_t(t)); }, xi0, T, n);
    CHECK(xb.norm() < 2.0 * pi);
    CHECK(w_body(maxabs(Mat3(exp_so3(xb) - Rbody)), where) <= 1e-10);

    // Product of exponentials, R ← R exp(h Ω(t + h/2)): order 2, error ~h² ≈ 1e-7 at h = 5e-4.
    Mat3 Rp = R0;
    const int np = 2000;
    for (int i = 0; i < np; ++i) Rp = Rp * exp_so3((T / np) * omega_of_t((i + 0.5) * T / np));
    CHECK(w_poe(maxabs(Mat3(exp_so3(xb) - Rp)), where) <= 1e-6);

    const Vec3 xs = rk4<Vec3>([](double t, const Vec3& x) { return dexpinv_space(x, omega_of_t(t)); }, xi0, T, n);
    CHECK(w_space(maxabs(Mat3(exp_so3(xs) - Rspace)), where) <= 1e-10);

    Vec3 c0 = Vec3::Zero();
    REQUIRE(cay_inv(R0, c0));
    const Vec3 xc = rk4<Vec3>([](double t, const Vec3& x) { return dcayinv_body(x, omega_of_t(t)); }, c0, T, n);
    CHECK(w_cay(maxabs(Mat3(cay(xc) - Rbody)), where) <= 1e-10);

    // The wrong trivialisation fails by O(1): this problem does discriminate the ½ sign.
    CHECK(w_teeth(maxabs(Mat3(exp_so3(xs) - Rbody)), where) > 1e-2);
  }
}

TEST_CASE("Ad and ad: exp(Ad_R ξ) = R exp(ξ) Rᵀ, ad(ξ, η) = ξ × η = [ξ̂, η̂]ˇ", "[lie][so3]") {
  const std::vector<Mat3> Rs = {Mat3::Identity(), exp_so3(Vec3(0.3, -0.2, 0.1)), exp_so3(Vec3(-1.0, 2.0, 0.5)),
                                exp_so3((pi - 1e-8) * Vec3(1.0, 2.0, 3.0).normalized())};
  Worst w_exp("exp(Ad_R xi) - R exp(xi) R^T (max entry)");
  Worst w_hat("R hat(xi) R^T - hat(R xi) / max(1,|xi|)");
  Worst w_ad("ad(xi,eta) - vee([hat xi, hat eta]) / (|xi||eta|)");
  for (const Sample& s : samples()) {
    INFO(describe(s));
    for (const Mat3& R : Rs) {
      CHECK(w_exp(maxabs(Mat3(exp_so3(Ad(R, s.xi)) - R * exp_so3(s.xi) * R.transpose())), describe(s)) <= 2e-15);
      CHECK(w_hat(maxabs(Mat3(R * hat(s.xi) * R.transpose() - hat(Ad(R, s.xi)))) / std::max(1.0, s.theta),
                  describe(s)) <= 2e-15);
      CHECK(maxabs(Vec3(Ad(compose(R, Rs[2]), s.xi) - Ad(R, Ad(Rs[2], s.xi)))) <= 2e-15 * std::max(1.0, s.theta));
      CHECK(maxabs(Mat3(compose(R, inverse(R)) - Mat3::Identity())) <= 1e-15);
    }
    for (const Vec3& eta : {kEta, kEta2}) {
      CHECK(ad(s.xi, eta) == s.xi.cross(eta));
      const Vec3 comm = vee(Mat3(hat(s.xi) * hat(eta) - hat(eta) * hat(s.xi)));
      CHECK(w_ad((ad(s.xi, eta) - comm).norm() / std::max(1e-300, s.xi.norm() * eta.norm()), describe(s)) <= 1e-15);
    }
  }
}

TEST_CASE("geodesic_distance and quat_distance agree and treat q and −q alike", "[lie][so3][quaternion]") {
  const Vec3 xa(0.4, -1.3, 0.7);
  const Mat3 A = exp_so3(xa);
  const Quat qa = quat_exp(xa);
  const Quat mqa(-qa.w(), -qa.x(), -qa.y(), -qa.z());
  Worst w_geo("geodesic_distance(A, A exp(xi)) - theta");
  Worst w_quat("quat_distance(qa, qa q(xi)) - theta (all sign choices)");
  Worst w_agree("geodesic_distance - quat_distance");
  for (const Sample& s : samples()) {
    INFO(describe(s));
    const Mat3 B = A * exp_so3(s.xi);
    const Quat qb = qa * quat_exp(s.xi);
    const Quat mqb(-qb.w(), -qb.x(), -qb.y(), -qb.z());
    const double th = s.xi.norm();
    CHECK(w_geo(std::abs(geodesic_distance(A, B) - th), describe(s)) <= 2e-15);
    CHECK(std::abs(geodesic_distance(B, A) - geodesic_distance(A, B)) <= 2e-15);
    for (const Quat& a : {qa, mqa}) {
      for (const Quat& b : {qb, mqb}) {
        CHECK(w_quat(std::abs(quat_distance(a, b) - th), describe(s)) <= 2e-15);
        CHECK(w_agree(std::abs(quat_distance(a, b) - geodesic_distance(matrix_from_quat(a), matrix_from_quat(b))),
                      describe(s)) <= 2e-15);
      }
    }
  }
}

TEST_CASE("Product state SO(3) × ℝ³: compose, inverse, retract_body", "[lie][product]") {
  const SO3xR3 a{exp_so3(Vec3(0.3, -0.2, 0.1)), Vec3(1.0, -2.0, 0.5)};
  const SO3xR3 b{exp_so3(Vec3(-1.0, 2.0, 0.5)), Vec3(-0.25, 4.0, 3.0)};
  const SO3xR3 c{exp_so3((pi - 1e-8) * Vec3(1.0, 2.0, 3.0).normalized()), Vec3(0.0, 0.1, -7.0)};
  auto dist = [](const SO3xR3& x, const SO3xR3& y) { return std::max(maxabs(Mat3(x.R - y.R)), maxabs(Vec3(x.Pi - y.Pi))); };
  const SO3xR3 id{};
  CHECK(dist(compose(a, id), a) == 0.0);
  CHECK(dist(compose(id, a), a) == 0.0);
  CHECK(dist(compose(a, inverse(a)), id) <= 1e-15);
  CHECK(dist(compose(inverse(a), a), id) <= 1e-15);
  CHECK(dist(inverse(inverse(a)), a) == 0.0);
  CHECK(dist(compose(compose(a, b), c), compose(a, compose(b, c))) <= 1e-15 * 8.0);
  // The ℝ³ factor is additive and independent of the attitude.
  CHECK(compose(a, b).Pi == a.Pi + b.Pi);
  CHECK(maxabs(Mat3(compose(a, b).R - a.R * b.R)) == 0.0);
  for (const Sample& s : samples()) {
    INFO(describe(s));
    const SO3xR3Tangent t{s.xi, Vec3(0.5, -0.25, 2.0) * s.theta};
    const SO3xR3 r = retract_body(a, t);
    CHECK(dist(r, compose(a, exp_product(t))) <= 1e-15);
    CHECK(maxabs(Mat3(r.R - a.R * exp_so3(s.xi))) == 0.0);
    // Retracting back with −t returns to a; the group difference recovers the tangent.
    CHECK(dist(retract_body(r, SO3xR3Tangent{-s.xi, -t.v}), a) <= 2e-15);
    const SO3xR3 d = compose(inverse(a), r);
    CHECK(maxabs(Vec3(d.Pi - t.v)) <= 1e-15 * std::max(1.0, t.v.norm()));
    if (s.theta < pi) CHECK((log_so3(d.R) - s.xi).norm() <= 1e-14);
  }
  CHECK(dist(retract_body(a, SO3xR3Tangent{}), a) == 0.0);
  CHECK(dist(exp_product(SO3xR3Tangent{}), id) == 0.0);
}

}  // namespace test_lie_so3_derivatives

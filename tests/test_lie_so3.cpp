// Property tests for the maps of lie/so3.hpp and lie/quaternion.hpp: hat/vee,
// exp and log (as matrices and through the quaternion), quat_from_matrix and
// the Cayley map, on the deterministic samples of support/so3_samples.hpp
// (θ across the series/closed-form switches and next to π).
//
// Independent references: a long-double Rodrigues formula (and long-double
// Taylor series for the dexp coefficients) and the quaternion path.
// Derivatives, Ad/ad, distances and the product state:
// test_lie_so3_derivatives.cpp.
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

#include "integrators/schemes/rkmk_pair_kernels.hpp"
#include "lie/exp_series.hpp"
#include "lie/product_state.hpp"
#include "lie/quaternion.hpp"
#include "lie/so3.hpp"
#include "support/worst_error.hpp"
#include "support/so3_samples.hpp"

namespace test_lie_so3 {  // this file's names, apart in the unity batches of lgi_tests (tests/CMakeLists.txt)

namespace {

using lgi::lie::Mat3;
using lgi::lie::Vec3;
using Quat = Eigen::Quaterniond;
using LD = long double;
using Mat3L = Eigen::Matrix<LD, 3, 3>;
using Vec3L = Eigen::Matrix<LD, 3, 1>;

constexpr double pi = std::numbers::pi;

using namespace lgi::testing;

// ---------------------------------------------------------------------------
// Long-double references (80-bit on x86-64: about 3 more decimal digits)

Mat3L hatL(const Vec3L& v) {
  Mat3L m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

/// Taylor series Σ_k (−1)^k θ^{2k} / (2k + m)!, summed until negligible.
LD alt_series(LD theta2, int m) {
  LD fact = 1;
  for (int i = 2; i <= m; ++i) fact *= static_cast<LD>(i);
  LD term = 1 / fact, sum = 0;
  for (int k = 0; k < 40; ++k) {
    sum += term;
    term *= -theta2 / (static_cast<LD>(2 * k + m + 1) * static_cast<LD>(2 * k + m + 2));
  }
  return sum;
}
LD coefA(LD t) { return t < 0.5L ? alt_series(t * t, 1) : std::sin(t) / t; }                 // sinθ/θ
LD coefB(LD t) { return t < 0.5L ? alt_series(t * t, 2) : (1 - std::cos(t)) / (t * t); }       // (1−cosθ)/θ²
LD coefC(LD t) { return t < 0.5L ? alt_series(t * t, 3) : (t - std::sin(t)) / (t * t * t); }   // (θ−sinθ)/θ³
/// c(θ) = (1 − (θ/2)cot(θ/2))/θ² = −Σ_{n≥1} (−1)^n B_{2n} θ^{2n−2}/(2n)! (Bernoulli numbers).
LD coefD(LD t) {
  if (t >= 0.1L) return (1 - (t / 2) * std::cos(t / 2) / std::sin(t / 2)) / (t * t);
  const LD B[] = {1.0L / 6, -1.0L / 30, 1.0L / 42, -1.0L / 30, 5.0L / 66, -691.0L / 2730, 7.0L / 6};
  LD sum = 0, pow = 1, fact = 2;  // θ^{2n−2}, (2n)!
  for (int n = 1; n <= 7; ++n) {
    const LD sign = (n % 2 == 0) ? 1 : -1;
    sum += -sign * B[n - 1] * pow / fact;
    pow *= t * t;
    fact *= static_cast<LD>((2 * n + 1) * (2 * n + 2));
  }
  return sum;
}

Mat3 exp_ref(const Vec3& xi) {
  const Vec3L x = xi.cast<LD>();
  const LD t = x.norm();
  const Mat3L X = hatL(x);
  return (Mat3L::Identity() + coefA(t) * X + coefB(t) * X * X).cast<double>();
}
Mat3 dexp_body_ref(const Vec3& xi) {
  const Vec3L x = xi.cast<LD>();
  const LD t = x.norm();
  const Mat3L X = hatL(x);
  return (Mat3L::Identity() - coefB(t) * X + coefC(t) * X * X).cast<double>();
}
Mat3 dexpinv_body_ref(const Vec3& xi) {
  const Vec3L x = xi.cast<LD>();
  const LD t = x.norm();
  const Mat3L X = hatL(x);
  return (Mat3L::Identity() + X / 2 + coefD(t) * X * X).cast<double>();
}
/// Unit quaternion (cos(θ/2), sin(θ/2) ξ/θ) of the stored ξ, rounded once.
Quat quat_ref(const Vec3& xi) {
  const Vec3L x = xi.cast<LD>();
  const LD t = x.norm();
  const LD s = t == 0 ? 0.5L : std::sin(t / 2) / t;
  return Quat(static_cast<double>(std::cos(t / 2)), static_cast<double>(s * x.x()), static_cast<double>(s * x.y()),
              static_cast<double>(s * x.z()));
}

}  // namespace

using namespace lgi::lie;

// ===========================================================================

TEST_CASE("hat and vee: hat(v) w = v × w, vee(hat(v)) = v", "[lie][so3]") {
  Worst w_cross("hat(v) w - v x w  / (|v||w|)");
  const std::vector<Vec3> ws = {kEta, kEta2, Vec3::UnitX(), Vec3(1e-9, 3.0, -2.0)};
  for (const Sample& s : samples()) {
    INFO(describe(s));
    const Mat3 X = hat(s.xi);
    CHECK(maxabs(Mat3(X + X.transpose())) == 0.0);  // exactly skew
    CHECK(vee(X) == s.xi);                         // (v − (−v))/2 is exact
    for (const Vec3& w : ws) {
      const double err = maxabs(Vec3(X * w - s.xi.cross(w))) / std::max(1e-300, s.xi.norm() * w.norm());
      CHECK(w_cross(err, describe(s)) <= 1e-16);
    }
  }
  // vee of a general matrix is the vee of its skew part.
  Mat3 M;
  M << 1.0, 2.0, -3.0, 0.5, -4.0, 7.0, 11.0, -6.0, 0.25;
  CHECK(maxabs(Vec3(vee(M) - vee(Mat3(0.5 * (M - M.transpose()))))) <= 1e-15);
}

TEST_CASE("exp, quat_exp, dexp and dexp^-1 match long-double references across the series switches", "[lie][so3]") {
  // The samples plus neighbours of the switches at 1e-4 and 1e-2, and large angles.
  std::vector<double> thetas(kAngles.begin(), kAngles.end());
  for (double t : {0.99999e-4, 1.00001e-4, 0.99999e-2, 1.00001e-2, 3e-3, 0.3, 0.5, 4.0, 6.0}) thetas.push_back(t);
  Worst w_exp("exp_so3 vs long-double Rodrigues (max entry)");
  Worst w_dexp("dexp_body vs long-double reference (max entry)");
  Worst w_dexpinv("dexpinv_body_matrix vs long-double reference / max(1,|M|)");
  Worst w_quat("quat_exp vs long-double quaternion (max comp)");
  for (double th : thetas) {
    for (const Vec3& n : axes()) {
      const Vec3 xi = th * n;
      std::ostringstream where;
      where.precision(17);
      where << "theta = " << th << ", n = (" << n.transpose() << ")";
      INFO(where.str());
      CHECK(w_exp(maxabs(Mat3(exp_so3(xi) - exp_ref(xi))), where.str()) <= 1e-15);
      CHECK(w_dexp(maxabs(Mat3(dexp_body(xi) - dexp_body_ref(xi))), where.str()) <= 1e-15);
      const Mat3 ref = dexpinv_body_ref(xi);
      CHECK(w_dexpinv(maxabs(Mat3(dexpinv_body_matrix(xi) - ref)) / std::max(1.0, maxabs(ref)), where.str()) <=
            1e-15);
      // quat_exp switches to its series at 1e-4 too.
      CHECK(w_quat((quat_exp(xi).coeffs() - quat_ref(xi).coeffs()).cwiseAbs().maxCoeff(), where.str()) <= 2.5e-16);
    }
  }
}

TEST_CASE("exp_series: the short series, the series and the closed forms of a, b, c agree with long double",
          "[lie][so3]") {
  // a = sinθ/θ, b = (1 − cosθ)/θ², c = (1 − (θ/2) cot(θ/2))/θ² in long double,
  // accurate to ~1e-19/θ² relative: θ² from 1e-2 up, across the bounds θ² = 1/4
  // (short series below) and θ² = 1 (closed forms above).
  namespace ex = lgi::lie::exp_series;
  Worst w_short("short series vs long double (relative)");
  Worst w_full("series vs long double (relative)");
  Worst w_closed("closed forms vs long double (relative)");
  int short_samples = 0;
  for (int i = 0; i <= 4000; ++i) {
    const double t2 = 0.01 + 1.2 * i / 4000.0;
    const long double th = std::sqrt(static_cast<long double>(t2)), T2 = t2;
    const long double ref[3] = {std::sin(th) / th, (1.0L - std::cos(th)) / T2,
                                (1.0L - 0.5L * th * std::cos(0.5L * th) / std::sin(0.5L * th)) / T2};
    const double full[3] = {ex::series_a(t2), ex::series_b(t2), ex::series_c(t2)};
    const double shrt[3] = {ex::series_a<true>(t2), ex::series_b<true>(t2), ex::series_c<true>(t2)};
    const auto m = lgi::integrators::rkmk_pair_detail::map_coefficients(t2);
    const double used[3] = {m.a, m.b, m.c};
    std::ostringstream where;
    where.precision(17);
    where << "theta^2 = " << t2;
    INFO(where.str());
    for (int k = 0; k < 3; ++k) {
      const auto rel = [&](double x) { return static_cast<double>(std::abs((x - ref[k]) / ref[k])); };
      if (t2 < 1.0) CHECK(w_full(rel(full[k]), where.str()) <= 3.5e-16);
      if (t2 < ex::short_series_bound) CHECK(w_short(rel(shrt[k]), where.str()) <= 3.5e-16);
      // The tier map_coefficients picks; above θ² = 1 the closed form of c
      // cancels (ε/θ² absolute, lie/exp_series.hpp), 12ε relative at θ = 1.
      if (t2 < 1.0) CHECK(rel(used[k]) <= 3.5e-16);
      else CHECK(w_closed(rel(used[k]), where.str()) <= (k == 2 ? 3e-15 : 6e-16));
    }
    if (t2 < ex::short_series_bound) {
      // The dropped terms fall below half an ulp and Estrin's grouping rounds
      // alike: the short series is the full one's value, bit for bit, only
      // one level shallower (also 10⁵ random θ² < 1/4 checked when written).
      ++short_samples;
      for (int k = 0; k < 3; ++k) CHECK(shrt[k] == full[k]);
      CHECK(m.a == shrt[0]);
      CHECK(m.c == shrt[2]);
    } else if (t2 < 1.0) {
      CHECK(m.a == full[0]);
      CHECK(m.c == full[2]);
    }
  }
  CHECK(short_samples > 500);
}

// Tolerances for exp_so3 as a matrix. The correctly rounded rotation has
// |RᵀR − I|_F ≈ 4e-16. The Rodrigues evaluation I + aξ̂ + bξ̂² rounds each entry
// several times, and for θ ≳ 2 the diagonal is 1 − b(θ² − ξᵢ²) with bθ² ≈ 2, so
// entries sit up to 5 ulp (1.1e-15) from the exact rotation, and |RᵀR − I|_F
// reaches 3.4e-15 for some axes (2000 pseudo-random axes, θ ∈ [1, 10]); on
// the fixed samples the worst is 1.3e-15 next to π. A 1e-15 Frobenius bound
// is therefore not attainable by exp_so3 (nor by the quaternion matrix, which
// rounds as often); the bounds below are the measured level with < 2× margin.
TEST_CASE("exp_so3 is orthogonal with det 1", "[lie][so3]") {
  Worst w_orth("|R^T R - I|_F for R = exp_so3(xi), samples");
  Worst w_orthmax("max entry |R^T R - I|, samples");
  Worst w_det("|det R - 1|, samples");
  auto all = samples();
  for (double th : {4.0, 10.0}) all.push_back({th, 3, th * axes()[3]});
  for (const Sample& s : all) {
    INFO(describe(s));
    const Mat3 R = exp_so3(s.xi);
    CHECK(w_orthmax(maxabs(Mat3(R.transpose() * R - Mat3::Identity())), describe(s)) <= 1e-15);
    CHECK(w_orth(orthogonality_error(R), describe(s)) <= 2e-15);
    CHECK(w_det(std::abs(R.determinant() - 1.0), describe(s)) <= 1e-15);
  }
}

TEST_CASE("exp_so3 on pseudo-random axes: entries, orthogonality, det", "[lie][so3]") {
  // splitmix64: the same axes on every platform.
  std::uint64_t state = 0x243F6A8885A308D3ULL;
  auto uniform = [&state]() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-52 - 1.0;  // [−1, 1)
  };
  Worst w_ent("max entry exp_so3 - long-double Rodrigues, random axes");
  Worst w_orth("|R^T R - I|_F, random axes");
  Worst w_det("|det R - 1|, random axes");
  for (int k = 0; k < 500; ++k) {
    const Vec3 n = Vec3(uniform(), uniform(), uniform()).normalized();
    for (double th : {1e-9, 1e-5, 5e-3, 0.5, 1.0, 2.0, 3.0, pi - 1e-8, pi, 10.0}) {
      const Vec3 xi = th * n;
      std::ostringstream where;
      where.precision(17);
      where << "theta = " << th << ", n = (" << n.transpose() << ")";
      INFO(where.str());
      const Mat3 R = exp_so3(xi);
      CHECK(w_ent(maxabs(Mat3(R - exp_ref(xi))), where.str()) <= 2e-15);
      CHECK(w_orth(orthogonality_error(R), where.str()) <= 5e-15);
      CHECK(w_det(std::abs(R.determinant() - 1.0), where.str()) <= 4e-15);
    }
  }
}

TEST_CASE("log ∘ exp = id for |ξ| < π (±ξ at π), exp ∘ log = id", "[lie][so3]") {
  Worst w_abs("|log(exp xi) - xi| / max(1, theta), theta < pi");
  Worst w_rel("|log(exp xi) - xi| / theta, 0 < theta < pi");
  Worst w_pi("min |log(exp xi) -+ xi| at theta = pi");
  Worst w_explog("max entry exp(log R) - R");
  for (const Sample& s : samples()) {
    INFO(describe(s));
    const Mat3 R = exp_so3(s.xi);
    const Vec3 r = log_so3(R);
    CHECK(r.norm() <= pi * (1.0 + 4.0 * std::numeric_limits<double>::epsilon()));  // |log R| ≤ π up to rounding
    if (s.theta < pi) {
      const double err = (r - s.xi).norm();
      CHECK(w_abs(err / std::max(1.0, s.theta), describe(s)) <= 1e-15);
      if (s.theta > 0.0) CHECK(w_rel(err / s.theta, describe(s)) <= 1e-15);
    } else {
      // |ξ| = π: log may return ξ or −ξ (both are rotation vectors of R).
      const double err = std::min((r - s.xi).norm(), (r + s.xi).norm());
      CHECK(w_pi(err, describe(s)) <= 1e-15 * pi);
    }
    CHECK(w_explog(maxabs(Mat3(exp_so3(r) - R)), describe(s)) <= 1e-15);
  }
  // Beyond π, log returns the equivalent vector (θ − 2π) n with |·| ≤ π.
  for (double th : {4.0, 5.5, 2.0 * pi - 1e-3}) {
    for (const Vec3& n : axes()) {
      INFO("theta = " << th << ", n = " << n.transpose());
      const Vec3 r = log_so3(exp_so3(th * n));
      CHECK((r - (th - 2.0 * pi) * n).norm() <= 1e-14);
    }
  }
  // Exact half-turns about the coordinate axes: log gives ±π e_i.
  for (int i = 0; i < 3; ++i) {
    Mat3 R = -Mat3::Identity();
    R(i, i) = 1.0;
    const Vec3 r = log_so3(R);
    INFO("half-turn about e" << i);
    CHECK(std::abs(std::abs(r(i)) - pi) <= 1e-15);
    CHECK(r.norm() == Approx(pi).epsilon(1e-15));
    CHECK(maxabs(Mat3(exp_so3(r) - R)) <= 1e-15);
  }
}

TEST_CASE("log near π is accurate to 1e-14 (matrix from exp, from long double, from the quaternion)", "[lie][so3]") {
  Worst w_exp("log(exp_so3(xi)) - xi, theta = pi - d");
  Worst w_ref("log(long-double R rounded) - xi, theta = pi - d");
  Worst w_quat("log(matrix_from_quat(q)) - xi, theta = pi - d");
  Worst w_qlog("quat_log(q) - xi, theta = pi - d");
  Worst w_naive("[teeth] arccos-of-trace angle error (must be large)");
  for (double d : {1e-6, 1e-8, 1e-10, 1e-12}) {
    for (const Vec3& n : axes()) {
      const Vec3 xi = (pi - d) * n;
      std::ostringstream where;
      where << "theta = pi - " << d << ", n = (" << n.transpose() << ")";
      INFO(where.str());
      const Quat q = quat_ref(xi);
      CHECK(w_exp((log_so3(exp_so3(xi)) - xi).norm(), where.str()) <= 1e-14);
      CHECK(w_ref((log_so3(exp_ref(xi)) - xi).norm(), where.str()) <= 1e-14);
      CHECK(w_quat((log_so3(matrix_from_quat(q)) - xi).norm(), where.str()) <= 1e-14);
      CHECK(w_qlog((quat_log(q) - xi).norm(), where.str()) <= 1e-14);
      if (d == 1e-8) {
        // The samples do discriminate: the textbook acos((tr R − 1)/2) loses half the digits here.
        const Mat3 R = exp_ref(xi);
        const double naive = std::acos(std::clamp(0.5 * (R.trace() - 1.0), -1.0, 1.0));
        CHECK(w_naive(std::abs(naive - xi.norm()), where.str()) > 1e-12);
      }
    }
  }
}

TEST_CASE("exp matches the quaternion path; quat_log inverts quat_exp", "[lie][so3][quaternion]") {
  Worst w_mat("matrix_from_quat(quat_exp(xi)) - exp_so3(xi) (max entry)");
  Worst w_norm("| |quat_exp(xi)| - 1 |");
  Worst w_log("quat_log(quat_exp(xi)) - xi / max(1,theta), theta < pi");
  Worst w_q("quat_exp(xi) - long-double quaternion (max comp)");
  for (const Sample& s : samples()) {
    INFO(describe(s));
    const Quat q = quat_exp(s.xi);
    // w = cos(|ξ|/2) ≥ 0 for |ξ| ≤ π; at the sample π·n, |ξ| may round one ulp above π and w to −1e-16.
    CHECK(q.w() >= -1e-15);
    CHECK(w_mat(maxabs(Mat3(matrix_from_quat(q) - exp_so3(s.xi))), describe(s)) <= 1e-15);
    CHECK(w_norm(std::abs(q.norm() - 1.0), describe(s)) <= 1e-15);
    CHECK(w_q((q.coeffs() - quat_ref(s.xi).coeffs()).cwiseAbs().maxCoeff(), describe(s)) <= 2.5e-16);
    if (s.theta < pi) {
      CHECK(w_log((quat_log(q) - s.xi).norm() / std::max(1.0, s.theta), describe(s)) <= 1e-15);
    }
    // q and −q give the same rotation vector.
    const Quat mq(-q.w(), -q.x(), -q.y(), -q.z());
    CHECK((quat_log(mq) - quat_log(q)).norm() <= 1e-15 * std::max(1.0, s.theta));
  }
}

TEST_CASE("quat_from_matrix: round trip with w ≥ 0 on all four Shepperd branches", "[lie][quaternion]") {
  std::vector<Quat> qs;
  for (const Sample& s : samples()) {
    const Quat q = quat_exp(s.xi);
    qs.push_back(q);
    qs.emplace_back(-q.w(), -q.x(), -q.y(), -q.z());  // the same attitude
  }
  // Half-turns about the axes, and quaternions dominated by each component with either sign of w.
  for (const std::array<double, 4>& c : std::vector<std::array<double, 4>>{{0, 1, 0, 0},
                                                                          {0, 0, 1, 0},
                                                                          {0, 0, 0, 1},
                                                                          {-0.1, 0.9, 0.3, -0.2},
                                                                          {0.2, -0.1, 0.95, 0.1},
                                                                          {-0.05, 0.1, -0.2, 0.97},
                                                                          {0.9, -0.3, 0.2, 0.1},
                                                                          {-0.9, -0.3, 0.2, 0.1},
                                                                          {0.5, 0.5, 0.5, 0.5},
                                                                          {1e-9, 0.6, -0.8, 0.0},
                                                                          {-1e-9, 0.0, 0.6, -0.8}}) {
    qs.push_back(Quat(c[0], c[1], c[2], c[3]).normalized());
  }
  std::array<int, 4> branch_hits{};  // trace, x, y, z: Shepperd's choice, replicated here
  Worst w_q("quat_from_matrix(R(q)) - (±q with w >= 0) (max comp)");
  Worst w_R("R(quat_from_matrix(R)) - R (max entry)");
  for (const Quat& q : qs) {
    INFO("q = (" << q.w() << ", " << q.x() << ", " << q.y() << ", " << q.z() << ")");
    const Mat3 R = matrix_from_quat(q);
    const double t = R.trace(), d0 = R(0, 0), d1 = R(1, 1), d2 = R(2, 2);
    const int branch = (t >= d0 && t >= d1 && t >= d2) ? 0 : (d0 >= d1 && d0 >= d2) ? 1 : (d1 >= d2) ? 2 : 3;
    ++branch_hits[static_cast<std::size_t>(branch)];
    const Quat p = quat_from_matrix(R);
    CHECK(p.w() >= 0.0);
    const Eigen::Vector4d expected = q.w() >= 0.0 ? q.coeffs() : Eigen::Vector4d(-q.coeffs());
    double err = (p.coeffs() - expected).cwiseAbs().maxCoeff();
    if (q.w() == 0.0) err = std::min(err, (p.coeffs() + expected).cwiseAbs().maxCoeff());  // ±q at w = 0
    CHECK(w_q(err, "") <= 1e-15);
    CHECK(w_R(maxabs(Mat3(matrix_from_quat(p) - R)), "") <= 1e-15);
  }
  INFO("hits: trace " << branch_hits[0] << ", x " << branch_hits[1] << ", y " << branch_hits[2] << ", z "
                      << branch_hits[3]);
  for (int hits : branch_hits) CHECK(hits >= 3);
}

TEST_CASE("Cayley: cay_inv round trip, quaternion (2, ξ)/√(4+θ²), angle 2 atan(θ/2)", "[lie][so3][cayley]") {
  auto all = samples();
  for (double th : {5.0, 10.0}) all.push_back({th, 4, th * axes()[4]});
  Worst w_inv("cay_inv(cay(xi)) - xi / max(1,theta)");
  Worst w_quat("cay(xi) - R((2,xi)/sqrt(4+theta^2)) (max entry)");
  Worst w_qfm("quat_from_matrix(cay(xi)) - (2,xi)/sqrt(4+theta^2)");
  Worst w_def("cay(xi) - (I - X/2)^-1 (I + X/2) (max entry)");
  Worst w_ang("geodesic angle of cay(xi) - 2 atan(theta/2)");
  Worst w_orth("|R^T R - I|_F for R = cay(xi)");
  for (const Sample& s : all) {
    INFO(describe(s));
    const double th = s.xi.norm();
    const Mat3 C = cay(s.xi);
    Vec3 back = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
    REQUIRE(cay_inv(C, back));
    CHECK(w_inv((back - s.xi).norm() / std::max(1.0, th), describe(s)) <= 1e-15);
    const Eigen::Vector4d qc = Eigen::Vector4d(2.0, s.xi.x(), s.xi.y(), s.xi.z()) / std::sqrt(4.0 + th * th);
    const Quat q(qc(0), qc(1), qc(2), qc(3));
    CHECK(w_quat(maxabs(Mat3(C - matrix_from_quat(q))), describe(s)) <= 1e-15);
    CHECK(w_qfm((quat_from_matrix(C).coeffs() - q.coeffs()).cwiseAbs().maxCoeff(), describe(s)) <= 1e-15);
    const Mat3 X = hat(s.xi);
    const Mat3 def = (Mat3::Identity() - 0.5 * X).inverse() * (Mat3::Identity() + 0.5 * X);
    CHECK(w_def(maxabs(Mat3(C - def)), describe(s)) <= 1e-15);
    CHECK(w_ang(std::abs(geodesic_distance(Mat3::Identity(), C) - 2.0 * std::atan(0.5 * th)), describe(s)) <=
          1e-15);
    CHECK(w_orth(orthogonality_error(C), describe(s)) <= 1e-15);
  }
  // cay⁻¹ does not exist for half-turns: cay_inv must say so.
  for (int i = 0; i < 3; ++i) {
    Mat3 R = -Mat3::Identity();
    R(i, i) = 1.0;
    Vec3 xi = Vec3::Zero();
    INFO("half-turn about e" << i);
    CHECK_FALSE(cay_inv(R, xi));
  }
}

}  // namespace test_lie_so3

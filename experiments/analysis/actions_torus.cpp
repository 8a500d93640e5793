// The actions of a torus found numerically from the flow (docs/actions.md §3).
//
// Chart: ZXZ Euler angles (docs/conventions.md §2); at fixed p_ψ = ℓ the
// reduced coordinates are (θ, φ, p_θ, p_φ) with the canonical one-form
// λ = p_θ dθ + p_φ dφ, and along the flow p_θ θ̇ + p_φ φ̇ = 2T − ℓψ̇.
// Section: p_θ = 0 crossed upwards, i.e. g = Π1Γ2 − Π2Γ1 rising
// (p_θ = g/sinθ). Cycle a is one of the k circles C of the section (every
// k-th point), fitted as a Fourier series of (Π, Γ) in α_j = jρ with ρ refined
// to make the fit smooth; cycle b is k returns of the flow closed by the arc
// of C back by ρ. Then
//   I_a = (1/2π)∮_C λ = (1/2π)∮_C Π3 (Γ2 dΓ1 − Γ1 dΓ2)/(Γ1² + Γ2²)   (p_θ = 0 on C),
//   ω_b = 2π/(k T̄), ω_a = 2πρ/(k T̄),  I_a ω_a + I_b ω_b = ⟨2T − ℓψ̇⟩   (time average),
// with ρ, T̄ and the time average as weighted Birkhoff averages.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <vector>

#include "experiments/analysis/actions.hpp"
#include "experiments/analysis/actions_support.hpp"
#include "integrators/registry.hpp"
#include "integrators/system/invariants.hpp"
#include "integrators/system/model.hpp"

namespace lgi::experiments {
namespace {

constexpr double pi = std::numbers::pi;

struct SectionPoint4 {
  double t = 0.0, theta = 0.0, phi = 0.0, p_theta = 0.0, p_phi = 0.0;
  Vec3 Pi = Vec3::Zero(), Gamma = Vec3::Zero();  // the curve is fitted in these (no chart pole)
};

SectionPoint4 section_coordinates(double t, const system::State& s) {
  const Vec3 gamma = s.R.row(2).transpose();
  const double sin_theta = std::hypot(gamma.x(), gamma.y());
  SectionPoint4 p;
  p.t = t;
  p.theta = std::atan2(sin_theta, gamma.z());
  p.phi = std::atan2(gamma.x(), gamma.y());
  p.p_theta = (s.Pi.x() * gamma.y() - s.Pi.y() * gamma.x()) / sin_theta;
  p.p_phi = s.Pi.z();
  p.Pi = s.Pi;
  p.Gamma = gamma;
  return p;
}

/// Keeps (t, 2T, ψ unwrapped) at every step and the section crossings.
class TorusRecorder final : public CrossingRecorder {
 public:
  TorusRecorder(const Mat3& J_inv, int wanted)
      : CrossingRecorder([](const system::State& s) { return s.Pi.x() * s.R(2, 1) - s.Pi.y() * s.R(2, 0); }, wanted),
        J_inv_(J_inv) {}
  void observe(std::int64_t, double t, const system::State& s) override {
    const double psi = std::atan2(s.R(0, 2), -s.R(1, 2));
    psi_.push_back(psi_.empty() ? psi : psi_.back() + std::remainder(psi - psi_.back(), 2.0 * pi));
    t_.push_back(t);
    two_T_.push_back(s.Pi.dot(J_inv_ * s.Pi));
  }
  /// ⟨2T − ℓψ̇⟩ over [0, τ] with the Birkhoff weight; ⟨ψ̇⟩ by parts, −(1/τ)∫w'ψ/∫w.
  double mean_pq(double l) const {
    const double tau = t_.back();
    double w_sum = 0.0, tw = 0.0, psi_w = 0.0;
    for (std::size_t j = 0; j < t_.size(); ++j) {
      const double s = t_[j] / tau;
      w_sum += birkhoff_weight(s);
      tw += birkhoff_weight(s) * two_T_[j];
      psi_w += birkhoff_weight_derivative(s) * psi_[j];
    }
    return tw / w_sum + l * psi_w / (tau * w_sum);
  }
  std::size_t samples() const { return t_.size(); }
  double t_end() const { return t_.empty() ? 0.0 : t_.back(); }

 private:
  Mat3 J_inv_;
  std::vector<double> t_, two_T_, psi_;
};

/// ρ from the angle increments of the section points: of φ itself where the
/// points wind around the φ-circle (mean resultant length of e^{iφ} below ½),
/// otherwise about their mean in the plane of the two principal components
/// of (θ, φ − φ̄, p_φ), each coordinate scaled to unit spread.
double rotation_number(const std::vector<SectionPoint4>& pts) {
  const Eigen::Index n = static_cast<Eigen::Index>(pts.size());
  double c = 0.0, s = 0.0;
  for (const auto& p : pts) c += std::cos(p.phi), s += std::sin(p.phi);
  const bool winds = std::hypot(c, s) < 0.5 * static_cast<double>(n);
  const double phi_bar = std::atan2(s, c);
  Eigen::MatrixXd Y(n, 3);
  for (Eigen::Index k = 0; k < n; ++k) {
    const auto& p = pts[static_cast<std::size_t>(k)];
    Y.row(k) << p.theta, std::remainder(p.phi - phi_bar, 2.0 * pi), p.p_phi;
  }
  Y.rowwise() -= Y.colwise().mean();
  for (Eigen::Index j = 0; j < 3; ++j) {
    const double spread = Y.col(j).norm() / std::sqrt(static_cast<double>(n));
    if (spread > 1e-12) Y.col(j) /= spread;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> pca(Y.transpose() * Y);
  const Eigen::Vector3d e1 = pca.eigenvectors().col(2), e2 = pca.eigenvectors().col(1);
  auto angle = [&](Eigen::Index k) {
    return winds ? pts[static_cast<std::size_t>(k)].phi : std::atan2(Y.row(k).dot(e2), Y.row(k).dot(e1));
  };
  // Increments lifted about their circular mean, not into (−π, π]: near ρ = ½ they straddle
  // ±π, and wrapped values alias (+π − ε and −π + ε average to about 0).
  std::vector<double> increments;
  double ci = 0.0, si = 0.0;
  for (Eigen::Index k = 1; k < n; ++k) {
    increments.push_back(std::remainder(angle(k) - angle(k - 1), 2.0 * pi));
    ci += std::cos(increments.back()), si += std::sin(increments.back());
  }
  const double centre = std::atan2(si, ci);
  for (double& d : increments) d = centre + std::remainder(d - centre, 2.0 * pi);
  return birkhoff_average(increments) / (2.0 * pi);
}

/// A least-squares Fourier fit of the section curve C in α_j = jρ mod 1, in the Cartesian
/// (Π, Γ) rather than the chart's (θ, φ, p_φ): near the chart's pole θ = 0 the curve
/// stays smooth in (Π, Γ) while φ swings by up to π over a few points.
struct CurveFit {
  Eigen::MatrixXd coef;  // (2M + 1) × 6: the series of Π1, Π2, Π3, Γ1, Γ2, Γ3
  double residual = 0.0, rms = 0.0;
  double gap = 0.0;  // largest gap between the α_j (fraction of the circle)
  int M = 0;
};

CurveFit fit_section_curve(const std::vector<SectionPoint4>& pts, double rho, int harmonics) {
  CurveFit f;
  const std::size_t n = pts.size();
  // Near a resonance ρ ≈ p/q the α_j fill q short arcs only, and a series whose shortest
  // wavelength 1/M is below twice the largest gap is not determined by the points (an alias
  // ρ fits anything): M is cut to 1/(2 gap), and fewer than 4 resolvable harmonics reject ρ.
  std::vector<double> alpha(n), sorted(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double kr = static_cast<double>(k) * rho;
    sorted[k] = alpha[k] = kr - std::floor(kr);
  }
  std::sort(sorted.begin(), sorted.end());
  f.gap = sorted.front() + 1.0 - sorted.back();
  for (std::size_t j = 1; j < n; ++j) f.gap = std::max(f.gap, sorted[j] - sorted[j - 1]);
  const int resolvable = f.gap > 0.0 ? static_cast<int>(std::floor(0.5 / f.gap)) : harmonics;
  f.M = std::max(1, std::min({harmonics, static_cast<int>(n) / 4, resolvable}));
  if (resolvable < 4) {
    f.residual = f.rms = std::numeric_limits<double>::infinity();
    return f;
  }
  const Eigen::Index rows = static_cast<Eigen::Index>(n);
  Eigen::MatrixXd D(rows, 2 * f.M + 1), V(rows, 6);
  for (Eigen::Index k = 0; k < rows; ++k) {
    const double a = alpha[static_cast<std::size_t>(k)];
    D(k, 0) = 1.0;
    for (int m = 1; m <= f.M; ++m) {
      D(k, 2 * m - 1) = std::cos(2.0 * pi * m * a);
      D(k, 2 * m) = std::sin(2.0 * pi * m * a);
    }
    const auto& p = pts[static_cast<std::size_t>(k)];
    V.row(k) << p.Pi.transpose(), p.Gamma.transpose();
  }
  f.coef = D.colPivHouseholderQr().solve(V);
  const Eigen::MatrixXd e = D * f.coef - V;
  f.residual = e.cwiseAbs().maxCoeff();
  f.rms = e.norm() / std::sqrt(static_cast<double>(e.size()));
  return f;
}

/// ρ refined so that the points lie on one smooth curve in α = jρ: the rms of the fit is
/// minimised on shrinking grids about the Birkhoff estimate (few harmonics first, whose
/// basin in ρ is wider). The conjugacy to the rotation makes the true ρ the minimiser
/// (cf. A. Luque & J. Villanueva, "Numerical computation of rotation numbers of
/// quasi-periodic planar curves", Physica D 238 (2009) 2025).
double refine_rotation_number(const std::vector<SectionPoint4>& pts, double rho, int harmonics) {
  double width = 1e-4;  // the Birkhoff estimate is good to ~1e-6; wider brackets meet resonant aliases
  for (int stage = 0; width > 1e-12; ++stage, width /= 5.0) {
    const int M = stage == 0 ? 3 : stage == 1 ? 8 : harmonics;
    double best = fit_section_curve(pts, rho, M).rms, arg = rho;
    for (int j = -10; j <= 10; ++j) {
      const double r = rho + width * j / 10.0, e = j == 0 ? best : fit_section_curve(pts, r, M).rms;
      if (e < best) best = e, arg = r;
    }
    rho = arg;
  }
  return rho;
}

/// (1/2π)∮_C λ on the fitted curve. On C p_θ = 0, so λ = p_θ dθ + p_φ dφ with
/// dθ = −dΓ3/sinθ, dφ = (Γ2 dΓ1 − Γ1 dΓ2)/sin²θ, p_θ sinθ = Π1Γ2 − Π2Γ1, p_φ = Π3;
/// the periodic trapezoid rule on q points (geometric convergence; q large since the
/// integrand is steep where C passes near the pole). Sets the winding of φ along C.
double section_curve_action(const CurveFit& f, int& winding) {
  const int q = std::max(4096, 16 * f.M);
  double sum = 0.0, turns = 0.0;
  for (int j = 0; j < q; ++j) {
    const double a = static_cast<double>(j) / q;
    Eigen::VectorXd x = f.coef.row(0).transpose(), dx = Eigen::VectorXd::Zero(6);
    for (int m = 1; m <= f.M; ++m) {
      const double c = std::cos(2.0 * pi * m * a), s = std::sin(2.0 * pi * m * a), w = 2.0 * pi * m;
      x += c * f.coef.row(2 * m - 1).transpose() + s * f.coef.row(2 * m).transpose();
      dx += w * (-s * f.coef.row(2 * m - 1).transpose() + c * f.coef.row(2 * m).transpose());
    }
    const double s2 = x(3) * x(3) + x(4) * x(4), phi_d = (x(4) * dx(3) - x(3) * dx(4)) / s2;
    sum += (x(0) * x(4) - x(1) * x(3)) * (-dx(5)) / s2 + x(2) * phi_d;
    turns += phi_d;
  }
  winding = static_cast<int>(std::lround(turns / q / (2.0 * pi)));
  return sum / q / (2.0 * pi);
}

/// The section of a torus cut by Σ in k circles that the return map permutes: every
/// k-th point lies on one circle, which the k-th return map rotates by ρ_k.
struct CircleFit {
  int k = 1;
  double rho = 0.0;
  CurveFit fit;
};

CircleFit fit_section_circles(const std::vector<SectionPoint4>& pts, const NumericalTorusOptions& options) {
  CircleFit best;
  best.fit.residual = std::numeric_limits<double>::infinity();
  for (int k = 1; k <= 3; ++k) {
    std::vector<SectionPoint4> circle;
    for (std::size_t j = 0; j < pts.size(); j += static_cast<std::size_t>(k)) circle.push_back(pts[j]);
    if (circle.size() < 64) break;
    const double rho = refine_rotation_number(circle, rotation_number(circle), options.harmonics);
    CircleFit c{k, rho, fit_section_curve(circle, rho, options.harmonics)};
    if (k == 1 || c.fit.residual < best.fit.residual) best = c;
    if (best.fit.residual < options.max_fit_residual) break;
  }
  return best;
}

}  // namespace

NumericalTorus numerical_torus(const system::Scene& scene, const system::State& x0,
                               const NumericalTorusOptions& options) {
  NumericalTorus r;
  const Mat3 J_inv = scene.inertia.inverse();
  const Vec3 gamma0 = x0.R.row(2).transpose();
  r.l = x0.Pi.dot(gamma0);
  const integrators::SchemeInfo* info = integrators::find_scheme(options.scheme);
  if (info == nullptr) {
    r.status = "unknown scheme " + options.scheme;
    return r;
  }
  TorusRecorder recorder(J_inv, options.crossings);
  integrators::RunConfig cfg;
  cfg.t_end = options.max_time;
  cfg.dt = options.dt;
  cfg.events = &recorder.events();
  cfg.stop = recorder.stop_flag();
  cfg.cpu_clock = false;
  system::State x = x0;
  const system::AnyModel model = system::make_model(scene);
  const auto stats = info->run(model, x, cfg, recorder);
  r.h = system::SceneInvariants(scene, model).energy(x0);
  r.t_end = recorder.t_end();
  r.crossings = static_cast<int>(recorder.hits().size());
  if (r.crossings < std::max(16, options.crossings)) {
    r.status = "only " + std::to_string(r.crossings) + " section crossings (" + stats.status + ")";
    return r;
  }
  std::vector<SectionPoint4> pts;
  std::vector<double> returns;
  for (const auto& hit : recorder.hits()) {
    pts.push_back(section_coordinates(hit.t, hit.state));
    if (pts.size() > 1) returns.push_back(pts.back().t - pts[pts.size() - 2].t);
  }
  r.return_time = birkhoff_average(returns);
  double spread = 0.0;
  for (const auto& p : pts) spread = std::max(spread, (p.Gamma - pts.front().Gamma).norm() + (p.Pi - pts.front().Pi).norm());
  if (spread < 1e-6) {
    r.status = "the section is one point (a periodic orbit, not a 2-torus)";
    return r;
  }
  const CircleFit c = fit_section_circles(pts, options);
  r.fit_residual = c.fit.residual;
  if (!std::isfinite(r.fit_residual)) {
    r.status = "the section points leave gaps in the angle kρ (near a resonance: more crossings)";
    return r;
  }
  double I_a = section_curve_action(c.fit, r.winding), rho = c.rho;
  if (I_a < 0.0) I_a = -I_a, rho = -rho;  // orient cycle a so that its action is ≥ 0
  rho -= std::round(rho);
  r.rotation_number = rho;  // of the k-th return map on one circle
  r.action_a = I_a;
  r.omega_b = 2.0 * pi / (c.k * r.return_time);  // cycle b: k returns, closed by an arc of the circle
  r.omega_a = rho * r.omega_b;
  r.mean_pq = recorder.mean_pq(r.l);
  r.action_b = (r.mean_pq - I_a * r.omega_a) / r.omega_b;
  // A section that is not k smooth circles permuted by the return map (an arc whose ends are
  // tangencies of the flow to Σ, a resonant or degenerate torus) shows as a large fit residual.
  r.ok = r.fit_residual < options.max_fit_residual;
  r.status = r.ok ? "ok (" + std::to_string(c.k) + " circle" + (c.k > 1 ? "s)" : ")")
                  : "the section is not k smooth circles (fit residual " + std::to_string(r.fit_residual) + ")";
  return r;
}

}  // namespace lgi::experiments

namespace lgi::experiments {

std::vector<system::State> level_set_states(const HeavyTopBody& body, double l, double h, int n) {
  std::vector<system::State> states;
  const Mat3 J_inv = body.J.inverse();
  const double golden = pi * (3.0 - std::sqrt(5.0));
  const int lattice = std::max(4 * n, 200);
  std::vector<Vec3> accessible;
  for (int i = 0; i < lattice; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / lattice, r = std::sqrt(1.0 - z * z), a = golden * i;
    const Vec3 g(r * std::cos(a), r * std::sin(a), z);
    if (l * l / (2.0 * g.dot(body.J * g)) + body.weight.dot(g) < h) accessible.push_back(g);
  }
  if (accessible.empty()) return states;
  const std::size_t stride = std::max<std::size_t>(1, accessible.size() / static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < accessible.size() && static_cast<int>(states.size()) < n; i += stride) {
    const Vec3 g = accessible[i];
    const double gJg = g.dot(body.J * g), kinetic = h - l * l / (2.0 * gJg) - body.weight.dot(g);
    const Vec3 f1 = (std::abs(g.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(g).normalized(), f2 = g.cross(f1);
    const double beta = golden * static_cast<double>(states.size());
    const Vec3 d = std::cos(beta) * f1 + std::sin(beta) * f2;
    system::State s;
    s.Pi = l * (body.J * g) / gJg + std::sqrt(2.0 * kinetic / d.dot(J_inv * d)) * d;
    s.R.row(0) = f1.transpose();
    s.R.row(1) = g.cross(f1).transpose();
    s.R.row(2) = g.transpose();
    states.push_back(s);
  }
  return states;
}

}  // namespace lgi::experiments

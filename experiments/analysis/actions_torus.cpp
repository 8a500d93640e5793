// The actions of a torus found numerically from the flow (docs/actions.md §3).
//
// Chart: ZXZ Euler angles (docs/conventions.md §2); at fixed p_ψ = ℓ the
// reduced coordinates are (θ, φ, p_θ, p_φ) with the canonical one-form
// λ = p_θ dθ + p_φ dφ, and along the flow p_θ θ̇ + p_φ φ̇ = 2T − ℓψ̇.
// Section: p_θ = 0 crossed upwards, i.e. g = Π1Γ2 − Π2Γ1 rising
// (p_θ = g/sinθ). Cycle a is the section curve C, cycle b one return of the
// flow closed by the arc of C back by the rotation number ρ. Then
//   I_a = (1/2π)∮_C λ                      (Fourier fit of C in the angle α_k = kρ),
//   ω_b = 2π/T̄, ω_a = 2πρ/T̄,  I_a ω_a + I_b ω_b = ⟨2T − ℓψ̇⟩   (time average),
// with ρ, T̄ and the time average as weighted Birkhoff averages.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
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
  std::vector<double> increments;
  for (Eigen::Index k = 1; k < n; ++k) increments.push_back(std::remainder(angle(k) - angle(k - 1), 2.0 * pi));
  return birkhoff_average(increments) / (2.0 * pi);
}

/// (1/2π)∮_C λ from a least-squares Fourier fit of C in α_k = kρ mod 1
/// (φ lifted along C, minus its winding 2πwα); sets the fit residual and w.
double section_curve_action(const std::vector<SectionPoint4>& pts, double rho, int harmonics, double& residual,
                            int& winding) {
  const std::size_t n = pts.size();
  std::vector<double> alpha(n);
  for (std::size_t k = 0; k < n; ++k) alpha[k] = static_cast<double>(k) * rho - std::floor(static_cast<double>(k) * rho);
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return alpha[a] < alpha[b]; });
  std::vector<double> lifted(n);
  double phi = pts[order[0]].phi;
  lifted[order[0]] = phi;
  for (std::size_t j = 1; j < n; ++j) {
    phi += std::remainder(pts[order[j]].phi - pts[order[j - 1]].phi, 2.0 * pi);
    lifted[order[j]] = phi;
  }
  phi += std::remainder(pts[order[0]].phi - pts[order[n - 1]].phi, 2.0 * pi);
  winding = static_cast<int>(std::lround((phi - lifted[order[0]]) / (2.0 * pi)));
  const int M = std::max(1, std::min(harmonics, static_cast<int>(n) / 4));
  const Eigen::Index rows = static_cast<Eigen::Index>(n), cols = 2 * M + 1;
  Eigen::MatrixXd D(rows, cols), V(rows, 3);
  for (Eigen::Index k = 0; k < rows; ++k) {
    const std::size_t i = static_cast<std::size_t>(k);
    D(k, 0) = 1.0;
    for (int m = 1; m <= M; ++m) {
      D(k, 2 * m - 1) = std::cos(2.0 * pi * m * alpha[i]);
      D(k, 2 * m) = std::sin(2.0 * pi * m * alpha[i]);
    }
    V.row(k) << pts[i].theta, pts[i].p_theta, lifted[i] - 2.0 * pi * winding * alpha[i];
  }
  const Eigen::MatrixXd coef = D.colPivHouseholderQr().solve(V);
  const Eigen::MatrixXd fit = D * coef;
  residual = (fit - V).cwiseAbs().maxCoeff();
  // p_φ is fitted too (it varies along C for a general top).
  Eigen::VectorXd pphi(rows);
  for (Eigen::Index k = 0; k < rows; ++k) pphi(k) = pts[static_cast<std::size_t>(k)].p_phi;
  const Eigen::VectorXd cp = D.colPivHouseholderQr().solve(pphi);
  residual = std::max(residual, (D * cp - pphi).cwiseAbs().maxCoeff());
  // ∫_0^1 (p_θ θ' + p_φ φ') dα on 8M + 8 equispaced points: exact for these trigonometric polynomials.
  const int q = 8 * M + 8;
  double sum = 0.0;
  for (int j = 0; j < q; ++j) {
    const double a = static_cast<double>(j) / q;
    double theta_d = 0.0, phi_d = 2.0 * pi * winding, p_theta = coef(0, 1), p_phi = cp(0);
    for (int m = 1; m <= M; ++m) {
      const double c = std::cos(2.0 * pi * m * a), s = std::sin(2.0 * pi * m * a), f = 2.0 * pi * m;
      theta_d += f * (-coef(2 * m - 1, 0) * s + coef(2 * m, 0) * c);
      phi_d += f * (-coef(2 * m - 1, 2) * s + coef(2 * m, 2) * c);
      p_theta += coef(2 * m - 1, 1) * c + coef(2 * m, 1) * s;
      p_phi += cp(2 * m - 1) * c + cp(2 * m) * s;
    }
    sum += p_theta * theta_d + p_phi * phi_d;
  }
  return sum / q / (2.0 * pi);
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
  double rho = rotation_number(pts);
  double I_a = section_curve_action(pts, rho, options.harmonics, r.fit_residual, r.winding);
  if (I_a < 0.0) I_a = -I_a, rho = -rho;  // orient cycle a so that its action is ≥ 0
  rho -= std::round(rho);
  r.rotation_number = rho;
  r.action_a = I_a;
  r.omega_b = 2.0 * pi / r.return_time;
  r.omega_a = rho * r.omega_b;
  r.mean_pq = recorder.mean_pq(r.l);
  r.action_b = (r.mean_pq - I_a * r.omega_a) / r.omega_b;
  // A section curve that is not one smooth circle in the angle kρ (the section cuts the torus
  // in several circles, or the chart's pole is near) shows as a large fit residual.
  r.ok = r.fit_residual < options.max_fit_residual;
  r.status = r.ok ? "ok" : "the section curve is not one smooth circle (fit residual " +
                               std::to_string(r.fit_residual) + ")";
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

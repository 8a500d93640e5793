// The actions of a torus found numerically from the flow (docs/actions.md §3).
//
// Chart: ZXZ Euler angles (docs/conventions.md §2); at fixed p_ψ = ℓ the
// reduced coordinates are (θ, φ, p_θ, p_φ) with the canonical one-form
// λ = p_θ dθ + p_φ dφ, and along the flow p_θ θ̇ + p_φ φ̇ = 2T − ℓψ̇.
// Section: F = c crossed rising, F a coordinate of (Π, Γ) and c a level free
// of F's turning values, both from a pilot run (actions_section.hpp). Cycle a
// is one of the k circles C of the section (every k-th point), fitted as a
// Fourier series of (Π, Γ) in α_j = jρ with ρ refined to make the fit smooth;
// cycle b is k returns of the flow closed by the arc of C back by ρ. Then
//   I_a = (1/2π)∮_C λ,  λ = [(Π1Γ2 − Π2Γ1)(−dΓ3) + Π3(Γ2 dΓ1 − Γ1 dΓ2)]/(Γ1² + Γ2²),
//   ω_b = 2π/(k T̄), ω_a = 2πρ/(k T̄),  I_a ω_a + I_b ω_b = ⟨2T − ℓψ̇⟩   (time average),
// with T̄ and the time average as weighted Birkhoff averages.
#include <Eigen/Dense>
#include <atomic>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <vector>

#include "experiments/analysis/actions.hpp"
#include "experiments/analysis/actions_section.hpp"
#include "experiments/analysis/actions_support.hpp"
#include "integrators/registry/registry.hpp"
#include "integrators/system/invariants.hpp"
#include "integrators/system/model.hpp"

namespace lgi::experiments {
namespace {

using std::numbers::pi;

struct SectionPoint4 {
  double t = 0.0;
  Vec3 Pi = Vec3::Zero(), Gamma = Vec3::Zero();  // the curve is fitted in these (no chart pole)
};

Point6 point6(const system::State& s) {
  Point6 p;
  p << s.Pi, s.R.row(2).transpose();
  return p;
}

/// The pilot run: every step's (Π, Γ), until `wanted` rising crossings of p_θ = 0 (the
/// turning points of Γ3, a clock of the slow motion) or `max_samples` steps.
class PilotRecorder final : public integrators::Observer {
 public:
  PilotRecorder(int wanted, std::size_t max_samples)
      : event_([](const system::State& s) { return s.Pi.x() * s.R(2, 1) - s.Pi.y() * s.R(2, 0); }),
        wanted_(wanted), max_samples_(max_samples) {}
  void observe(std::int64_t, double, const system::State& s) override {
    samples.push_back(point6(s));
    if (samples.size() >= max_samples_ || interrupt_requested.load(std::memory_order_relaxed)) stop_.store(true);
  }
  void on_event(const integrators::EventHit&) override {
    if (++hits_ >= wanted_) stop_.store(true);
  }
  const integrators::EventFunctions& events() const { return event_; }
  const std::atomic<bool>* stop_flag() const { return &stop_; }
  std::vector<Point6> samples;

 private:
  RisingEvent event_;
  int wanted_, hits_ = 0;
  std::size_t max_samples_;
  std::atomic<bool> stop_{false};
};

/// Keeps (t, 2T, ψ and φ unwrapped) at every step and the crossings of the section F = c.
class TorusRecorder final : public CrossingRecorder {
 public:
  TorusRecorder(const Mat3& J_inv, const SectionChoice& section, int wanted)
      : CrossingRecorder([section](const system::State& s) { return point6(s)[section.coordinate] - section.level; },
                         wanted),
        J_inv_(J_inv) {}
  void observe(std::int64_t, double t, const system::State& s) override {
    poll_interrupt();
    if (!t_.empty() && !(t > t_.back())) return;  // a continued run starts with the last state again
    const double psi = std::atan2(s.R(0, 2), -s.R(1, 2)), phi = std::atan2(s.R(2, 0), s.R(2, 1));
    psi_.push_back(psi_.empty() ? psi : psi_.back() + std::remainder(psi - psi_.back(), 2.0 * pi));
    phi_.push_back(phi_.empty() ? phi : phi_.back() + std::remainder(phi - phi_.back(), 2.0 * pi));
    t_.push_back(t);
    two_T_.push_back(s.Pi.dot(J_inv_ * s.Pi));
  }
  /// ⟨2T − ℓψ̇⟩ over [0, τ] with the Birkhoff weight.
  double mean_pq(double l) const { return mean(two_T_) - l * mean_rate(psi_); }
  /// ⟨φ̇⟩, φ unwrapped step by step (a slip of 2π near the chart's pole moves it by 2π/τ,
  /// far below what the rounding of the lift of ρ in numerical_torus can see).
  double mean_phi_rate() const { return mean_rate(phi_); }
  double t_end() const { return t_.empty() ? 0.0 : t_.back(); }

 private:
  double mean(const std::vector<double>& f) const {
    const double tau = t_.back();
    double w_sum = 0.0, fw = 0.0;
    for (std::size_t j = 0; j < t_.size(); ++j) {
      w_sum += birkhoff_weight(t_[j] / tau);
      fw += birkhoff_weight(t_[j] / tau) * f[j];
    }
    return fw / w_sum;
  }
  /// The weighted mean of ḟ by parts, −(1/τ)∫w'f/∫w (the weight vanishes at both ends).
  double mean_rate(const std::vector<double>& f) const {
    const double tau = t_.back();
    double w_sum = 0.0, fw = 0.0;
    for (std::size_t j = 0; j < t_.size(); ++j) {
      w_sum += birkhoff_weight(t_[j] / tau);
      fw += birkhoff_weight_derivative(t_[j] / tau) * f[j];
    }
    return -fw / (tau * w_sum);
  }
  Mat3 J_inv_;
  std::vector<double> t_, two_T_, psi_, phi_;
};

/// ρ from the angle increments of the section points, weighted-Birkhoff averaged: of φ itself
/// where the points wind around the φ-circle (mean resultant length of e^{iφ} below ½),
/// otherwise about their mean in the plane of the two principal components of (Π, Γ), each
/// coordinate scaled to unit spread. Very accurate where that angle is a circle coordinate (a
/// section about the symmetry axis of a Lagrange top), useless where it is not.
double birkhoff_rotation_number(const std::vector<SectionPoint4>& pts) {
  const Eigen::Index n = static_cast<Eigen::Index>(pts.size());
  double c = 0.0, s = 0.0;
  std::vector<double> phi;
  for (const auto& p : pts) phi.push_back(std::atan2(p.Gamma.x(), p.Gamma.y()));
  for (const double f : phi) c += std::cos(f), s += std::sin(f);
  const bool winds = std::hypot(c, s) < 0.5 * static_cast<double>(n);
  const double phi_bar = std::atan2(s, c);
  (void)phi_bar;
  Eigen::MatrixXd Y(n, 6);
  for (Eigen::Index k = 0; k < n; ++k) {
    const auto& p = pts[static_cast<std::size_t>(k)];
    Y.row(k) << p.Pi.transpose(), p.Gamma.transpose();
  }
  Y.rowwise() -= Y.colwise().mean();
  for (Eigen::Index j = 0; j < 6; ++j) {
    const double spread = Y.col(j).norm() / std::sqrt(static_cast<double>(n));
    if (spread > 1e-12) Y.col(j) /= spread;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> pca(Y.transpose() * Y);
  const Eigen::VectorXd e1 = pca.eigenvectors().col(5), e2 = pca.eigenvectors().col(4);
  auto angle = [&](Eigen::Index k) {
    return winds ? phi[static_cast<std::size_t>(k)] : std::atan2(Y.row(k).dot(e2), Y.row(k).dot(e1));
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
  bool limited = false;  // M was cut below the harmonics asked for by the number of points or the gap
};

CurveFit fit_section_curve(const std::vector<SectionPoint4>& pts, double rho, int harmonics, double pi_scale) {
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
  f.limited = f.M < harmonics;
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
    V.row(k) << p.Pi.transpose() / pi_scale, p.Gamma.transpose();  // Π relative to its largest |Π|
  }
  f.coef = D.colPivHouseholderQr().solve(V);
  const Eigen::MatrixXd e = D * f.coef - V;
  f.residual = e.cwiseAbs().maxCoeff();
  f.rms = e.norm() / std::sqrt(static_cast<double>(e.size()));
  f.coef.leftCols(3) *= pi_scale;
  return f;
}

/// ρ refined so that the points lie on one smooth curve in α = jρ: the rms of the fit is
/// minimised on shrinking grids about the polygon estimate (few harmonics first, whose
/// basin in ρ is wider). The conjugacy to the rotation makes the true ρ the minimiser
/// (cf. A. Luque & J. Villanueva, "Numerical computation of rotation numbers of
/// quasi-periodic planar curves", Physica D 238 (2009) 2025).
double refine_rotation_number(const std::vector<SectionPoint4>& pts, double rho, int harmonics, double pi_scale) {
  // The polygon estimate is within a few 1/m² of ρ (m = min(n, 400) points); within that
  // bracket the rms of the full fit has one minimum (its aliases lie 1/(nM) and more away).
  const double m = static_cast<double>(std::min<std::size_t>(pts.size(), 400));
  for (double width = 2.0 / (m * m); width > 1e-13; width /= 5.0) {
    double best = fit_section_curve(pts, rho, harmonics, pi_scale).rms, arg = rho;
    for (int j = -10; j <= 10; ++j) {
      const double r = rho + width * j / 10.0, e = j == 0 ? best : fit_section_curve(pts, r, harmonics, pi_scale).rms;
      if (e < best) best = e, arg = r;
    }
    rho = arg;
  }
  return rho;
}

/// (1/2π)∮_C λ on the fitted curve: λ = p_θ dθ + p_φ dφ with
/// dθ = −dΓ3/sinθ, dφ = (Γ2 dΓ1 − Γ1 dΓ2)/sin²θ, p_θ sinθ = Π1Γ2 − Π2Γ1, p_φ = Π3;
/// the periodic trapezoid rule on q points (geometric convergence; q large since the
/// integrand is steep where C passes near the pole). Sets the winding of φ along C and the
/// least sin²θ = Γ1² + Γ2² on C.
double section_curve_action(const CurveFit& f, int& winding, double& least_sin2) {
  const int q = std::max(4096, 16 * f.M);
  double sum = 0.0, turns = 0.0;
  least_sin2 = std::numeric_limits<double>::infinity();
  for (int j = 0; j < q; ++j) {
    const double a = static_cast<double>(j) / q;
    Eigen::VectorXd x = f.coef.row(0).transpose(), dx = Eigen::VectorXd::Zero(6);
    for (int m = 1; m <= f.M; ++m) {
      const double c = std::cos(2.0 * pi * m * a), s = std::sin(2.0 * pi * m * a), w = 2.0 * pi * m;
      x += c * f.coef.row(2 * m - 1).transpose() + s * f.coef.row(2 * m).transpose();
      dx += w * (-s * f.coef.row(2 * m - 1).transpose() + c * f.coef.row(2 * m).transpose());
    }
    const double s2 = x(3) * x(3) + x(4) * x(4), phi_d = (x(4) * dx(3) - x(3) * dx(4)) / s2;
    least_sin2 = std::min(least_sin2, s2);
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
  bool one_circle = false;  // k > 1 fitted, but the other returns lie on the same circle
};

/// The median distance of the points (Π relative to pi_scale, Γ) to the fitted curve,
/// sampled at 8192 values of α.
double median_distance_to_curve(const CurveFit& f, const std::vector<SectionPoint4>& pts, double pi_scale) {
  constexpr int q = 8192;
  std::vector<Point6> curve(q);
  for (int j = 0; j < q; ++j) {
    const double a = static_cast<double>(j) / q;
    Point6 x = f.coef.row(0).transpose();
    for (int m = 1; m <= f.M; ++m)
      x += std::cos(2.0 * pi * m * a) * f.coef.row(2 * m - 1).transpose() +
           std::sin(2.0 * pi * m * a) * f.coef.row(2 * m).transpose();
    x.head<3>() /= pi_scale;
    curve[static_cast<std::size_t>(j)] = x;
  }
  std::vector<double> d;
  for (const auto& p : pts) {
    const Point6 y = (Point6() << p.Pi / pi_scale, p.Gamma).finished();
    double least = std::numeric_limits<double>::infinity();
    for (const Point6& x : curve) least = std::min(least, (x - y).squaredNorm());
    d.push_back(std::sqrt(least));
  }
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

/// The most circles a section may cut from a torus.
constexpr int max_circles = 6;

CircleFit fit_section_circles(const std::vector<SectionPoint4>& pts, const NumericalTorusOptions& options) {
  CircleFit best;
  best.fit.residual = std::numeric_limits<double>::infinity();
  double pi_scale = 0.0;
  for (const auto& p : pts) pi_scale = std::max(pi_scale, p.Pi.norm());
  for (int k = 1; k <= max_circles; ++k) {
    std::vector<SectionPoint4> circle;
    std::vector<Point6> y;
    for (std::size_t j = 0; j < pts.size(); j += static_cast<std::size_t>(k)) {
      circle.push_back(pts[j]);
      y.push_back((Point6() << pts[j].Pi / pi_scale, pts[j].Gamma).finished());
    }
    if (circle.size() < 64) break;
    // Two first estimates (docs/actions.md §3, step 2), each refined; the better fit is kept.
    for (const double rho0 : {polygon_rotation_number(y), std::abs(birkhoff_rotation_number(circle))}) {
      const double rho =
          refine_rotation_number(circle, rho0, std::min(options.harmonics, options.refine_harmonics), pi_scale);
      CircleFit c{k, rho, fit_section_curve(circle, rho, options.harmonics, pi_scale)};
      if (!(best.fit.residual <= c.fit.residual)) best = c;
    }
    if (best.fit.residual < options.max_fit_residual) break;
  }
  // Every k-th point on one circle does not make k circles: on a single circle with ρ ≈ m/k the
  // first estimates can miss ρ while the k-th return map, rotating by kρ − m, is fitted. Then one
  // of ρ = (ρ_k + m)/k fits all the points, and cycle b is one return, not k.
  if (best.k > 1 && best.fit.residual < options.max_fit_residual) {
    for (int m = 0; m < best.k; ++m) {
      const double rho0 = (best.rho + m) / best.k;
      const double rho = refine_rotation_number(pts, rho0, std::min(options.harmonics, options.refine_harmonics), pi_scale);
      CircleFit one{1, rho, fit_section_curve(pts, rho, options.harmonics, pi_scale)};
      if (one.fit.residual < options.max_fit_residual) return one;
    }
    // No single ρ fits, yet if the next returns lie on the same circle the section is one circle
    // and cycle b = k returns is not a basis cycle: the actions would be wrong, so it is refused.
    std::vector<SectionPoint4> next;
    for (std::size_t j = 1; j < pts.size() && next.size() < 256; j += static_cast<std::size_t>(best.k))
      next.push_back(pts[j]);
    best.one_circle = median_distance_to_curve(best.fit, next, pi_scale) < 5e-3;
  }
  return best;
}

/// The failure of a torus (docs/actions.md §3): its reason and status; actions and frequencies stay NaN.
NumericalTorus failed(NumericalTorus r, TorusFailure reason, const std::string& status) {
  r.ok = false;
  r.reason = static_cast<int>(reason);
  r.status = status;
  r.action_a = r.action_b = r.omega_a = r.omega_b = std::numeric_limits<double>::quiet_NaN();
  return r;
}

/// The run of an orbit of the torus: to max_time at step dt, with the recorder's events, until
/// the recorder stops it.
template <class Recorder>
integrators::RunConfig orbit_config(const NumericalTorusOptions& options, Recorder& recorder) {
  integrators::RunConfig cfg;
  cfg.t_end = options.max_time;
  cfg.dt = options.dt;
  cfg.events = &recorder.events();
  cfg.stop = recorder.stop_flag();
  cfg.cpu_clock = false;
  return cfg;
}

/// The section from a pilot run of the same orbit: every step's (Π, Γ) until `pilot_turns`
/// turning points of Γ3 (docs/actions.md §3, step 1). Not tied to the crossings asked for: a
/// different section may cut other cycles, and runs with other --crossings must agree.
SectionChoice pilot_section(const integrators::SchemeInfo& info, const system::AnyModel& model,
                            const system::State& x0, const NumericalTorusOptions& options) {
  PilotRecorder pilot(options.pilot_turns, 200000);
  system::State x = x0;
  info.run(model, x, orbit_config(options, pilot), pilot);
  return choose_section(pilot.samples, options.min_section_window);
}

}  // namespace

NumericalTorus numerical_torus(const system::Scene& scene, const system::State& x0,
                               const NumericalTorusOptions& options) {
  NumericalTorus r;
  const Mat3 J_inv = scene.inertia.inverse();
  r.l = x0.Pi.dot(x0.R.row(2).transpose());
  const integrators::SchemeInfo* info = integrators::find_scheme(options.scheme);
  if (info == nullptr) return failed(r, TorusFailure::scheme, "unknown scheme " + options.scheme);
  const system::AnyModel model = system::make_model(scene);
  r.h = system::SceneInvariants(scene, model).energy(x0);
  r.section = pilot_section(*info, model, x0, options);
  if (r.section.coordinate < 0)
    return failed(r, TorusFailure::no_section,
                  "no transverse section: every coordinate of (Pi, Gamma) has turning values across its range");
  TorusRecorder recorder(J_inv, r.section, options.crossings);
  integrators::RunConfig cfg = orbit_config(options, recorder);
  system::State x = x0;
  std::vector<SectionPoint4> pts;
  CircleFit c;
  // Where the fit fails (mostly because the points cannot resolve the harmonics the curve needs:
  // too few points per circle, or gaps near a resonance ρ ≈ p/q), the run goes on to twice the
  // crossings, up to max_extend times those asked for (docs/actions.md §3, step 3).
  for (int wanted = options.crossings;; wanted *= 2) {
    recorder.extend(wanted);
    const auto stats = info->run(model, x, cfg, recorder);
    cfg.t0 = stats.t_final;
    r.t_end = recorder.t_end();
    r.crossings = static_cast<int>(recorder.hits().size());
    if (r.crossings < std::max(16, wanted))
      return failed(r, TorusFailure::crossings,
                    "only " + std::to_string(r.crossings) + " section crossings (" + stats.status + ")");
    std::vector<double> returns;
    pts.clear();
    for (const auto& hit : recorder.hits()) {
      pts.push_back({hit.t, hit.state.Pi, hit.state.R.row(2).transpose()});
      if (pts.size() > 1) returns.push_back(pts.back().t - pts[pts.size() - 2].t);
    }
    r.return_time = birkhoff_average(returns);
    double spread = 0.0;
    for (const auto& p : pts)
      spread = std::max(spread, (p.Gamma - pts.front().Gamma).norm() + (p.Pi - pts.front().Pi).norm());
    if (spread < 1e-6)
      return failed(r, TorusFailure::periodic, "the section is one point (a periodic orbit, not a 2-torus)");
    c = fit_section_circles(pts, options);
    r.fit_residual = c.fit.residual;
    if (r.fit_residual < options.max_fit_residual || 2 * wanted > options.max_extend * options.crossings)
      break;
  }
  if (!std::isfinite(r.fit_residual))
    return failed(r, TorusFailure::resonance,
                  "the section points leave gaps in the angle k rho after " + std::to_string(r.crossings) +
                      " crossings (near a resonance)");
  if (c.one_circle)
    return failed(r, TorusFailure::fit,
                  "the section is one circle met every " + std::to_string(c.k) +
                      "th return, but no single rotation number fits it (raise the crossings or lower --dt)");
  if (!(r.fit_residual < options.max_fit_residual))
    return failed(r, TorusFailure::fit, "the section is not k <= " + std::to_string(max_circles) + " smooth circles (fit residual " +
                                            std::to_string(r.fit_residual) + " after " + std::to_string(r.crossings) +
                                            " crossings)");
  double least_sin2 = 0.0;
  double I_a = section_curve_action(c.fit, r.winding, least_sin2), rho = c.rho;
  // Through the chart's pole λ is singular and I_a is off by a multiple of ℓ (docs/actions.md §3):
  // refused rather than reported.
  if (least_sin2 < options.min_pole_distance * options.min_pole_distance)
    return failed(r, TorusFailure::chart_pole,
                  "the section curve passes within " + std::to_string(std::sqrt(least_sin2)) +
                      " rad of the chart's pole Gamma = +-e3, where p dq is singular");
  // Cycle b: k returns closed by the arc of the circle back by ρ + m. Where C winds about the
  // φ-circle, m makes b's net turn of φ zero (k T̄⟨φ̇⟩/2π = w(ρ + m)); for the Lagrange top b is
  // then the nutation cycle and I_b = I_θ (docs/actions.md §3, step 4). Else ρ ∈ (−½, ½].
  const double phi_turns = c.k * r.return_time * recorder.mean_phi_rate() / (2.0 * pi);
  rho += r.winding != 0 ? std::round(phi_turns / r.winding - rho) : -std::round(rho);
  if (I_a < 0.0) I_a = -I_a, rho = -rho;  // orient cycle a so that its action is ≥ 0
  r.rotation_number = rho;  // of the k-th return map on one circle
  r.action_a = I_a;
  r.omega_b = 2.0 * pi / (c.k * r.return_time);
  r.omega_a = rho * r.omega_b;
  r.mean_pq = recorder.mean_pq(r.l);
  r.action_b = (r.mean_pq - I_a * r.omega_a) / r.omega_b;
  r.circles = c.k;
  for (std::size_t j = 0; j < pts.size(); j += static_cast<std::size_t>(c.k))
    r.circle.push_back((Point6() << pts[j].Pi, pts[j].Gamma).finished());
  r.ok = true;
  r.status = "ok (" + std::to_string(c.k) + " circle" + (c.k > 1 ? "s)" : ")");
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

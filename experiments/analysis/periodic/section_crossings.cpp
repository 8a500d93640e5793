#include "experiments/analysis/periodic/section_crossings.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "experiments/analysis/cardan_section.hpp"
#include "experiments/io/trajectory_observer.hpp"  // interrupt_requested

namespace lgi::experiments {

namespace {

double heavy_value(const HeavyTopBody& body, const PhaseSection& s, const Vec6& x) {
  const Vec3 Pi = x.head<3>(), G = x.tail<3>();
  if (s.kind == SectionKind::gamma) return G.dot(s.axis);
  return (body.J.inverse() * Pi).dot(s.axis.cross(G));
}

Vec6 heavy_gradient(const HeavyTopBody& body, const PhaseSection& s, const Vec6& x) {
  Vec6 g = Vec6::Zero();
  if (s.kind == SectionKind::gamma) {
    g.tail<3>() = s.axis;
    return g;
  }
  const Eigen::Matrix3d Jinv = body.J.inverse();
  const Vec3 Pi = x.head<3>(), G = x.tail<3>();
  g.head<3>() = Jinv * s.axis.cross(G);  // J⁻¹ is symmetric
  g.tail<3>() = (Jinv * Pi).cross(s.axis);
  return g;
}

/// The gradient of a Cardan factor: ∇q̇2 = (−(M⁻¹ ∂M/∂q_k M⁻¹ p)_2, (M⁻¹)_2·), or cos q2 e_q2.
Vec6 cardan_gradient(const system::CardanTop& top, const Vec6& x, int which) {
  Vec6 g = Vec6::Zero();
  if (which == 1) {
    g(1) = std::cos(x(1));
    return g;
  }
  const Vec3 q = x.head<3>();
  const Mat3 Minv = top.mass_matrix(q).inverse();
  const Vec3 v = Minv * x.tail<3>();
  const auto dM = top.mass_matrix_derivatives(q);
  for (int k = 0; k < 3; ++k) g(k) = -Minv.row(1).dot(dM[static_cast<std::size_t>(k)] * v);
  g.tail<3>() = Minv.row(1).transpose();
  return g;
}

/// The factors of the whole section function: S itself (a heavy top), or q̇2 and sin q2.
int factor_count(const PeriodicFlow& flow) { return flow.cardan ? 2 : 1; }
double factor_value(const PeriodicFlow& flow, const PhaseSection& s, const Vec6& x, int which) {
  return flow.cardan ? cardan_section_factor(*flow.cardan, system::unstack(x), which) : heavy_value(flow.body, s, x);
}

/// The crossing of factor `which` inside the step from x (value f0) of size dt (f1 at its end):
/// Illinois regula falsi on τ.
bool refine(const PeriodicFlow& flow, const PhaseSection& sec, int which, const Vec6& x, double dt, double f0,
            double f1, double& tau, Vec6& at) {
  double a = 0.0, b = dt, fa = f0, fb = f1;
  int side = 0;
  for (int it = 0; it < 60; ++it) {
    tau = (a * fb - b * fa) / (fb - fa);
    at = x;
    if (!flow_step(flow, at, tau)) return false;
    const double f = factor_value(flow, sec, at, which);
    if (std::abs(f) <= 1e-13 || std::abs(b - a) <= 4.0 * std::numeric_limits<double>::epsilon() * std::abs(dt)) break;
    if ((f < 0.0) == (fa < 0.0)) {
      a = tau, fa = f;
      if (side == -1) fb *= 0.5;
      side = -1;
    } else {
      b = tau, fb = f;
      if (side == 1) fa *= 0.5;
      side = 1;
    }
  }
  return true;
}

}  // namespace

double section_value(const PeriodicFlow& flow, const PhaseSection& s, const Vec6& x) {
  return factor_value(flow, s, x, s.cardan_factor < 0 ? 0 : s.cardan_factor);
}

Vec6 section_gradient(const PeriodicFlow& flow, const PhaseSection& s, const Vec6& x) {
  return flow.cardan ? cardan_gradient(*flow.cardan, x, s.cardan_factor < 0 ? 0 : s.cardan_factor)
                     : heavy_gradient(flow.body, s, x);
}

double section_rate(const PeriodicFlow& flow, const PhaseSection& s, const Vec6& x) {
  const Vec6 f = flow_field(flow, x);
  if (!flow.cardan) return heavy_gradient(flow.body, s, x).dot(f);
  // S = −sin q2 · q̇2: dS/dt = −cos q2 · q̇2² − sin q2 · q̈2.
  return -std::cos(x(1)) * f(1) * f(1) - std::sin(x(1)) * cardan_gradient(*flow.cardan, x, 0).dot(f);
}

PhaseSection section_at(const PeriodicFlow& flow, const PhaseSection& s, const Vec6& x) {
  if (!flow.cardan) return s;
  PhaseSection at = s;
  const Vec3 v = flow.cardan->velocity(system::unstack(x));
  const double speed = v.tail<2>().norm();
  at.cardan_factor = std::abs(std::sin(x(1))) < (speed > 0.0 ? std::abs(v(1)) / speed : 1.0) ? 1 : 0;
  return at;
}

SectionPoint section_coordinates(const PeriodicFlow& flow, const PhaseSection& s, const Vec6& x) {
  if (!flow.cardan) return section_point(s.kind, s.axis, x.tail<3>(), x.head<3>(), flow.body.J.inverse());
  const int which = section_at(flow, s, x).cardan_factor;
  const CardanCrossing c = cardan_crossing_at(*flow.cardan, system::unstack(x), 0.0, which, 1);
  return {c.x_coord, c.y_coord, c.piece};
}

std::vector<SectionCrossing> section_crossings(const PeriodicFlow& flow, const PhaseSection& s, const Vec6& x0,
                                               double t_span, double dt, std::size_t max_count, int direction,
                                               bool& ok) {
  std::vector<SectionCrossing> out;
  ok = true;
  const auto n = static_cast<long>(std::ceil(std::abs(t_span) / dt - 1e-9));
  const long steps = n < 1 ? 1 : n;
  const double h = t_span / static_cast<double>(steps);
  const int factors = factor_count(flow);
  Vec6 x = x0;
  double sx[2] = {factor_value(flow, s, x, 0), factors > 1 ? factor_value(flow, s, x, 1) : 0.0};
  for (long k = 0; k < steps && out.size() < max_count; ++k) {
    Vec6 y = x;
    if (interrupt_requested.load(std::memory_order_relaxed) || !flow_step(flow, y, h)) {  // Ctrl-C: as a failure
      ok = false;
      return out;
    }
    std::vector<SectionCrossing> step;  // this step's crossings, of either factor, in time order
    double sy[2] = {0.0, 0.0};
    for (int which = 0; which < factors; ++which) {
      sy[which] = factor_value(flow, s, y, which);
      if (sx[which] == 0.0 || !(sy[which] == 0.0 || (sx[which] < 0.0) != (sy[which] < 0.0))) continue;
      SectionCrossing c;
      double tau = h;
      if (sy[which] != 0.0 && !refine(flow, s, which, x, h, sx[which], sy[which], tau, c.x)) {
        ok = false;
        return out;
      }
      if (sy[which] == 0.0) c.x = y;
      c.t = static_cast<double>(k) * h + tau;
      // dS/dt in the sense of time, whatever the sense of integration.
      c.direction = section_rate(flow, s, c.x) >= 0.0 ? 1 : -1;
      // A start on the section (round-off) is not a crossing of its own.
      const bool at_start = k == 0 && std::abs(c.t) <= 1e-6 * std::abs(h);
      if (!at_start && (direction == 0 || c.direction == direction)) step.push_back(c);
    }
    std::sort(step.begin(), step.end(), [](const auto& a, const auto& b) { return std::abs(a.t) < std::abs(b.t); });
    for (const SectionCrossing& c : step)
      if (out.size() < max_count) out.push_back(c);
    x = y, sx[0] = sy[0], sx[1] = sy[1];
  }
  return out;
}

namespace {

template <int M>
bool newton_onto(const PeriodicFlow& flow, Vec6& x, double h, double l, const PhaseSection* section) {
  const Eigen::Vector3d levels = invariant_levels(flow, h, l);
  for (int it = 0; it < 12; ++it) {
    const Invariants inv = flow_invariants(flow, x);
    Eigen::Matrix<double, M, 1> r;
    Eigen::Matrix<double, M, 6> G;
    r.template head<3>() = inv.value - levels;
    G.template topRows<3>() = inv.gradients;
    if constexpr (M == 4) r(3) = section_value(flow, *section, x), G.row(3) = section_gradient(flow, *section, x);
    if (r.cwiseAbs().maxCoeff() <= 1e-13 * (1.0 + x.norm())) return x.allFinite();
    x -= G.transpose() * (G * G.transpose()).partialPivLu().solve(r);
  }
  return false;
}

}  // namespace

bool project_to_level(const PeriodicFlow& flow, Vec6& x, double h, double l, const PhaseSection* section) {
  return section ? newton_onto<4>(flow, x, h, l, section) : newton_onto<3>(flow, x, h, l, nullptr);
}

}  // namespace lgi::experiments

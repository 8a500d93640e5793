#include "experiments/analysis/periodic/section_crossings.hpp"

#include <Eigen/LU>
#include <cmath>
#include <limits>

#include "experiments/io/trajectory_observer.hpp"  // interrupt_requested

namespace lgi::experiments {

double section_value(const HeavyTopBody& body, const PhaseSection& s, const Vec6& x) {
  const Vec3 Pi = x.head<3>(), G = x.tail<3>();
  if (s.kind == SectionKind::gamma) return G.dot(s.axis);
  return (body.J.inverse() * Pi).dot(s.axis.cross(G));
}

Vec6 section_gradient(const HeavyTopBody& body, const PhaseSection& s, const Vec6& x) {
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

SectionPoint section_coordinates(const HeavyTopBody& body, const PhaseSection& s, const Vec6& x) {
  return section_point(s.kind, s.axis, x.tail<3>(), x.head<3>(), body.J.inverse());
}

namespace {

/// The crossing inside the step from x (S = s0) of size dt (S = s1 at its end): Illinois regula falsi on τ.
bool refine(const HeavyTopBody& body, const PhaseSection& sec, const Vec6& x, double dt, double s0, double s1,
            double& tau, Vec6& at) {
  double a = 0.0, b = dt, fa = s0, fb = s1;
  int side = 0;
  for (int it = 0; it < 60; ++it) {
    tau = (a * fb - b * fa) / (fb - fa);
    at = x;
    if (!flow_step(body, at, tau)) return false;
    const double f = section_value(body, sec, at);
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

std::vector<SectionCrossing> section_crossings(const HeavyTopBody& body, const PhaseSection& s, const Vec6& x0,
                                               double t_span, double dt, std::size_t max_count, int direction,
                                               bool& ok) {
  std::vector<SectionCrossing> out;
  ok = true;
  const auto n = static_cast<long>(std::ceil(std::abs(t_span) / dt - 1e-9));
  const long steps = n < 1 ? 1 : n;
  const double h = t_span / static_cast<double>(steps);
  Vec6 x = x0;
  double sx = section_value(body, s, x);
  for (long k = 0; k < steps && out.size() < max_count; ++k) {
    Vec6 y = x;
    if (interrupt_requested.load(std::memory_order_relaxed) || !flow_step(body, y, h)) {  // Ctrl-C: as a failure
      ok = false;
      return out;
    }
    const double sy = section_value(body, s, y);
    if (sx != 0.0 && (sy == 0.0 || (sx < 0.0) != (sy < 0.0))) {
      SectionCrossing c;
      double tau = h;
      if (sy != 0.0 && !refine(body, s, x, h, sx, sy, tau, c.x)) {
        ok = false;
        return out;
      }
      if (sy == 0.0) c.x = y;
      c.t = static_cast<double>(k) * h + tau;
      // dS/dt in the sense of time, whatever the sense of integration.
      c.direction = section_gradient(body, s, c.x).dot(euler_poisson_field(body, c.x)) >= 0.0 ? 1 : -1;
      // A start on the section (S round-off) is not a crossing of its own.
      const bool at_start = k == 0 && std::abs(c.t) <= 1e-6 * std::abs(h);
      if (!at_start && (direction == 0 || c.direction == direction)) out.push_back(c);
    }
    x = y, sx = sy;
  }
  return out;
}

namespace {

template <int M>
bool newton_onto(const HeavyTopBody& body, Vec6& x, double h, double l, const PhaseSection* section) {
  for (int it = 0; it < 12; ++it) {
    const Invariants inv = euler_poisson_invariants(body, x);
    Eigen::Matrix<double, M, 1> r;
    Eigen::Matrix<double, M, 6> G;
    r.template head<3>() = inv.value - Eigen::Vector3d(h, l, 1.0);
    G.template topRows<3>() = inv.gradients;
    if constexpr (M == 4) r(3) = section_value(body, *section, x), G.row(3) = section_gradient(body, *section, x);
    if (r.cwiseAbs().maxCoeff() <= 1e-13 * (1.0 + x.norm())) return x.allFinite();
    x -= G.transpose() * (G * G.transpose()).partialPivLu().solve(r);
  }
  return false;
}

}  // namespace

bool project_to_level(const HeavyTopBody& body, Vec6& x, double h, double l, const PhaseSection* section) {
  return section ? newton_onto<4>(body, x, h, l, section) : newton_onto<3>(body, x, h, l, nullptr);
}

}  // namespace lgi::experiments

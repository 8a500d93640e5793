#include "experiments/io/scene_suspension.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include <Eigen/Eigenvalues>

#include "integrators/system/terms/gravity.hpp"

namespace lgi::experiments {

using namespace scene_toml;

namespace {

double non_negative(const Table& t, std::string_view key, double fallback) {
  const toml::node* n = t.get(key);
  if (!n) return fallback;
  const double v = t.number(key, *n);
  if (!(v >= 0.0)) t.fail(*n, key, "must be >= 0, got " + fmt(v));
  return v;
}

lie::Vec3 non_negative_moments(const Table& t, std::string_view key) {
  const toml::node* n = t.get(key);
  if (!n) t.fail_here(key, "missing (required: the inner ring's principal moments [A, B, C], >= 0; 0 for a massless ring)");
  const lie::Vec3 m = t.vec3(key, *n);
  for (int i = 0; i < 3; ++i)
    if (!(m[i] >= 0.0)) t.fail(*n, key, "moment " + std::to_string(i + 1) + " must be >= 0, got " + fmt(m[i]));
  return m;
}

}  // namespace

void read_suspension(const Table& t, system::Scene& s) {
  if (!t.present()) return;
  constexpr std::array<std::string_view, 7> keys = {"tilt",       "outer_inertia", "inner_inertia", "outer_mass",
                                                    "outer_center", "inner_mass",  "inner_center"};
  t.check_keys(keys);
  system::SuspensionParameters p;
  const toml::node* tilt = t.get("tilt");
  if (!tilt) t.fail_here("tilt", "missing (required: the outer axis' angle from the vertical, in [0, pi])");
  p.tilt = t.number("tilt", *tilt);
  if (!(p.tilt >= 0.0 && p.tilt <= std::numbers::pi)) t.fail(*tilt, "tilt", "must be in [0, pi], got " + fmt(p.tilt));
  if (!t.get("outer_inertia"))
    t.fail_here("outer_inertia", "missing (required: the outer ring's moment about its axis, >= 0)");
  p.outer_inertia = non_negative(t, "outer_inertia", 0.0);
  p.inner_inertia = non_negative_moments(t, "inner_inertia");
  p.outer_mass = non_negative(t, "outer_mass", 0.0);
  p.inner_mass = non_negative(t, "inner_mass", 0.0);
  if (const toml::node* n = t.get("outer_center")) p.outer_center = t.vec3("outer_center", *n);
  if (const toml::node* n = t.get("inner_center")) p.inner_center = t.vec3("inner_center", *n);
  if (!s.center_of_mass)
    t.fail_here("", "a suspension needs a body with a fixed point: [body] center_of_mass is missing, so the body "
                    "is a free body (give center_of_mass = [0, 0, 0] for a body held at its centre of mass)");
  const int others = s.declared_terms() - (s.declared<system::GravityTerm>() ? 1 : 0);
  if (others > 0) t.fail_here("", "a Cardan-suspended top takes [gravity] only, no other torque table");
  if ((p.outer_mass > 0.0 || p.inner_mass > 0.0) && !s.declared<system::GravityTerm>())
    t.fail_here(p.outer_mass > 0.0 ? "outer_mass" : "inner_mass", "ring masses need [gravity]");
  s.suspension = p;
}

void read_cardan_initial(const Table& initial, system::Scene& s) {
  const toml::node* angles = initial.get("cardan_angles");
  const toml::node* rates = initial.get("cardan_rates");
  if (!s.suspension) {
    if (angles) initial.fail(*angles, "cardan_angles", "needs a [suspension] table");
    if (rates) initial.fail(*rates, "cardan_rates", "needs a [suspension] table");
    return;
  }
  for (std::string_view key : {"quaternion", "euler_zxz", "rotation_vector", "matrix", "gamma", "angular_velocity",
                               "angular_momentum", "euler_zxz_rates"})
    if (const toml::node* n = initial.get(key))
      initial.fail(*n, key, "a scene with [suspension] gives its state as cardan_angles and cardan_rates");
  if (!angles) initial.fail_here("cardan_angles", "missing (required with [suspension]: [q1, q2, q3] in radians)");
  if (!rates) initial.fail_here("cardan_rates", "missing (required with [suspension]: [q1dot, q2dot, q3dot] in rad/s)");
  const lie::Vec3 q = initial.vec3("cardan_angles", *angles);
  const lie::Vec3 qdot = initial.vec3("cardan_rates", *rates);
  const system::CardanTop top = cardan_top(s);
  const lie::Mat3 M = top.mass_matrix(q);
  const double smallest = Eigen::SelfAdjointEigenSolver<lie::Mat3>(M, Eigen::EigenvaluesOnly).eigenvalues()[0];
  if (!(smallest > 1e-12 * M.norm()))
    initial.fail(*angles, "cardan_angles",
                 "the mass matrix is singular here (q2 = " + fmt(q[1]) +
                     " is gimbal lock, sin q2 = 0, and the rings are massless): start away from it or give the "
                     "rings inertia in [suspension]");
  s.cardan_initial = top.from_rates(q, qdot);
  s.initial = top.body_state(s.cardan_initial);
}

system::CardanTop cardan_top(const system::Scene& s) {
  system::CardanTop top;
  top.J = s.inertia;
  top.mass = s.mass.value_or(0.0);
  top.chi = s.center_of_mass.value_or(lie::Vec3::Zero());
  if (const auto& g = s.declared<system::GravityTerm>()) top.g = g->g;
  top.suspension = s.suspension.value_or(system::SuspensionParameters{});
  return top;
}

}  // namespace lgi::experiments

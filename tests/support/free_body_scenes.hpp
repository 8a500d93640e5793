#pragma once
// Free-body test cases for the exact free-rigid-body flow
// (integrators/system/free_body_exact.hpp): the free-body scenes of
// experiments/scenes/ hard-coded (R0 = I, Π0 = J Ω0 where the scene gives Ω0),
// a rotated book with a non-diagonal inertia tensor, orbits on and next to the
// separatrix, symmetric and spherical bodies; their spans and sample times.
#include <string>
#include <vector>

#include "integrators/system/free_body_exact.hpp"
#include "lie/so3.hpp"

namespace lgi::testing {

struct Scene {
  std::string name;
  lie::Mat3 J;
  lie::Mat3 R0;
  lie::Vec3 Pi0;
  double span;  // > 0: absolute; < 0: that many periods of Π(t)
};

inline lie::Mat3 diag(double a, double b, double c) { return lie::Vec3(a, b, c).asDiagonal(); }

// Free-body scenes of experiments/scenes/ (hard-coded: the scene reader is
// written elsewhere), R0 = I, and Π0 = J Ω0 where the scene gives Ω0.
inline const lie::Mat3 kBook = diag(0.01203, 0.0074, 0.0048);  // dzhanibekov_book_axis{1,2,3}.toml
inline Scene book(int axis) {
  lie::Vec3 w(0.01, 0.01, 0.01);
  w(axis - 1) = 10.0;
  return {"dzhanibekov_book_axis" + std::to_string(axis), kBook, lie::Mat3::Identity(), kBook * w, -100.0};
}
inline Scene prism() {  // prism_edurev.toml
  const lie::Mat3 J = diag(5.0, 20.0, 17.0);
  return {"prism_edurev", J, lie::Mat3::Identity(), J * lie::Vec3(0.0, 0.01, 1.0), -100.0};
}
inline Scene hlw() {  // free_body_hlw.toml (its exact decimals)
  return {"free_body_hlw", diag(2.0, 1.0, 0.6666666666666666), lie::Mat3::Identity(),
          lie::Vec3(0.4535961214255773, 0.0, 0.8912073600614354), -100.0};
}
// The book with a non-diagonal inertia tensor: body axes turned by A, and a
// general initial attitude. Against the references only the well-conditioned
// spins: for axis 2 (k'² = 3.5e-6) the ulps by which the rounded tensor and its
// eigen-decomposition miss the diagonal book change the period as the double
// reference's errors do; it appears in the conservation and flow tests.
inline const lie::Mat3 kTurn = lgi::lie::exp_so3(lie::Vec3(0.4, 0.1, -0.7));
inline const lie::Mat3 kR0 = lgi::lie::exp_so3(lie::Vec3(0.3, -0.2, 0.5));
inline Scene rotated_book(int axis) {
  Scene s = book(axis);
  s.name = "rotated book, axis " + std::to_string(axis);
  s.J = kTurn * kBook * kTurn.transpose();
  s.Pi0 = kTurn * s.Pi0;
  s.R0 = kR0;
  return s;
}
// On the separatrix exactly: I = (2, 3, 6), Π = (1, ½, 1) gives
// 2H = ½ + 1/12 + 1/6 = ¾ and |Π|² = 9/4, so 2H/|Π|² = 1/3 = 1/I2
// (1/I1 + 1/I3 = 2/I2 makes Δ = G² − 2H I2 = (Π3² − Π1²)/2, and the flow forms
// Δ I1 I3 = Π3² (I3 − I2) I1 − Π1² (I2 − I1) I3 = 6 − 6 exactly). ±1e-12 on Π3 puts Π
// Δ/|Π|² = ±4.4e-13 off it: rotation about the largest/smallest axis with
// k'² = 1.8e-12, periods 238.6. Spans to t = 50 (λ = ¼: u runs from 0.35 to
// 12.85 ≈ K − 2, deep into the approach to the saddle).
inline Scene separatrix(double offset, const std::string& name) {
  return {name, diag(2.0, 3.0, 6.0), kR0, lie::Vec3(1.0, 0.5, 1.0 + offset), 50.0};
}
// The other homoclinic orbits: Π1 and Π3 of opposite signs.
inline Scene separatrix_crossed() { return {"separatrix, Pi1 Pi3 < 0", diag(2.0, 3.0, 6.0), kR0, lie::Vec3(-1.0, 0.5, 1.0), 50.0}; }
inline Scene symmetric_oblate() { return {"symmetric (1, 1, 2)", diag(1.0, 1.0, 2.0), kR0, lie::Vec3(0.3, 0.4, 1.0), -100.0}; }
inline Scene symmetric_prolate() { return {"symmetric (3, 1, 3)", diag(3.0, 1.0, 3.0), kR0, lie::Vec3(0.5, 0.8, -0.2), -100.0}; }
inline Scene spherical() { return {"spherical", diag(2.0, 2.0, 2.0), kR0, lie::Vec3(0.3, -1.2, 0.7), 50.0}; }

inline double span_of(const Scene& s, const system::FreeBodyExactFlow& f) {
  return s.span > 0.0 ? s.span : -s.span * f.momentum_period();
}

// Sample times: N = 997 (prime) equal steps, so that over 100 periods the
// samples visit every phase of Π(t) (not only the slow part near t = 0).
inline std::vector<double> sample_times(double span, int n = 997) {
  std::vector<double> t;
  for (int i = 1; i <= n; ++i) t.push_back(span * i / n);
  return t;
}

}  // namespace lgi::testing

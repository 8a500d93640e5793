#pragma once
// Compensated (Kahan–Babuška) summation of a scheme's state updates.
//
// A one-step method written as y_{n+1} = y_n + δ_n loses about ε|y| to
// rounding in every addition, and those errors need not average out: over
// 10⁸ steps of dmv the energy error grew like n^0.84. Carrying the rounding
// error of each addition into the next (Kahan, CACM 8 (1965) 40; Babuška,
// IFIP 1968) leaves an error of about ε|δ| per step, which behaves like a
// random walk (Hairer, McLachlan & Razakarivony, BIT 48 (2008) 231–243,
// §2 and eq. (2.3)):
//   d = δ − c;  t = y + d;  c = (t − y) − d;  y = t.
// The carry c is part of the scheme's state, not of the observed state: the
// run observes y, the rounded sum. This needs IEEE arithmetic as written
// (no -ffast-math; -ffp-contract=off keeps (t − y) − d from being fused),
// which is the project's floating-point policy (cmake/warnings.cmake).
namespace lgi::integrators {

/// y += delta with the rounding error carried in `carry` (componentwise for Eigen types).
template <class V>
void add_compensated(V& y, const V& delta, V& carry) {
  const V d = delta - carry;
  const V t = y + d;
  carry = (t - y) - d;
  y = t;
}

}  // namespace lgi::integrators

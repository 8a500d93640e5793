#pragma once
// Commutator-free Lie-group method of order 4 (CF4).
//
// Celledoni, Marthinsen & Owren, "Commutator-free Lie group methods",
// Future Gener. Comput. Syst. 19 (2003) 341–352, the order-4 scheme of §4
// (their eq. (12)), in body form (docs/math.md §4):
//   R_2 = R_n exp(½h Ω_1),  R_3 = R_n exp(½h Ω_2),  R_4 = R_2 exp(h Ω_3 − ½h Ω_1),
//   R_{n+1} = R_n exp(h(Ω_1/4 + Ω_2/6 + Ω_3/6 − Ω_4/12)) exp(h(−Ω_1/12 + Ω_2/6 + Ω_3/6 + Ω_4/4)),
// with Π advanced by classical RK4 (nodes c = (0, ½, ½, 1)). Order 4; two
// exponentials per update and no commutators. Conserves RᵀR = I to round-off.
// R exp(ŵ) row by row with the series coefficients of rkmk_pair_kernels.hpp
// (no sin or cos below θ = 1), and a stage attitude only in the rows the
// torque reads (TermTraits::attitude_rows), as the RKMK schemes form it.
#include "integrators/schemes/rkmk_pair_kernels.hpp"
#include "integrators/core/scheme_interface.hpp"

namespace lgi::integrators {

class Cf4 {
 public:
  static constexpr SchemeFacts facts{
      .order = 4, .reference = "Celledoni, Marthinsen & Owren, Future Gener. Comput. Syst. 19 (2003)"};
  template <class Model>
  StepStatus step(const Model& model, State& s, double t, double h, WorkCounters& work) const {
    using rkmk_pair_detail::times_exp;
    const double half = 0.5 * h;
    const unsigned rows = rkmk_pair_detail::torque_rows(model);  // of a stage attitude the torque reads
    const Vec3 O1 = model.omega(s.Pi);
    const Vec3 K1 = model.momentum_rate(s.R, s.Pi, O1, t);

    const Vec3 P2 = s.Pi + half * K1;
    const Vec3 O2 = model.omega(P2);
    Mat3 R2 = s.R;  // stage attitudes only matter when a torque reads them
    if constexpr (Model::has_torque) R2 = times_exp(s.R, half * O1, rows);
    const Vec3 K2 = model.momentum_rate(R2, P2, O2, t + half);

    const Vec3 P3 = s.Pi + half * K2;
    const Vec3 O3 = model.omega(P3);
    Mat3 R3 = s.R;  // stage attitudes only matter when a torque reads them
    if constexpr (Model::has_torque) R3 = times_exp(s.R, half * O2, rows);
    const Vec3 K3 = model.momentum_rate(R3, P3, O3, t + half);

    const Vec3 P4 = s.Pi + h * K3;
    const Vec3 O4 = model.omega(P4);
    Mat3 R4 = s.R;  // stage attitudes only matter when a torque reads them
    if constexpr (Model::has_torque) R4 = times_exp(R2, h * O3 - half * O1, rows);  // row i needs R2's row i
    const Vec3 K4 = model.momentum_rate(R4, P4, O4, t + h);

    const Vec3 first = O1 / 4.0 + O2 / 6.0 + O3 / 6.0 - O4 / 12.0;
    const Vec3 second = -O1 / 12.0 + O2 / 6.0 + O3 / 6.0 + O4 / 4.0;
    s.R = times_exp(times_exp(s.R, h * first), h * second);
    s.Pi += (h / 6.0) * (K1 + 2.0 * K2 + 2.0 * K3 + K4);
    work.rhs_evaluations += 4;
    return {};
  }
};

}  // namespace lgi::integrators

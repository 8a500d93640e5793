#pragma once
// The state spaces the one time loop (stepper_loop.hpp) runs on, as a small
// trait, after odeint's State template parameter and Sophus's group traits:
// the loop, its observer, events and checkpoints are templates on the state
// type S, and StateSpace<S> says what the loop needs of S beyond copying it.
//  - name: the space, for messages ("SO(3) x R^3", "T^3 x R^3");
//  - dimension and write/read: the state as that many doubles, in a fixed
//    order, for checkpoints and tables (bit for bit: no arithmetic);
//  - finite(): whether every entry is finite (x − x is 0 for a finite x and
//    NaN otherwise: one branch a step instead of one per entry).
// A model names its state type as Model::state_type; the rigid-body models
// of SO(3) × ℝ³ do not, and their state is system::State (state_of).
#include <cstddef>

#include "integrators/system/rigid_body.hpp"
#include "integrators/system/torus_state.hpp"

namespace lgi::integrators {

template <class S>
struct StateSpace;

/// SO(3) × ℝ³: (R, Π), written as R column by column (its storage order), then Π.
template <>
struct StateSpace<system::State> {
  static constexpr const char* name = "SO(3) x R^3";
  static constexpr std::size_t dimension = 12;
  static bool finite(const system::State& s) {
    double z = 0.0;
    for (int i = 0; i < 9; ++i) z += s.R.data()[i] - s.R.data()[i];
    for (int i = 0; i < 3; ++i) z += s.Pi.data()[i] - s.Pi.data()[i];
    return z == 0.0;
  }
  static void write(const system::State& s, double* out) {
    for (int i = 0; i < 9; ++i) out[i] = s.R.data()[i];
    for (int i = 0; i < 3; ++i) out[9 + i] = s.Pi(i);
  }
  static void read(const double* in, system::State& s) {
    for (int i = 0; i < 9; ++i) s.R.data()[i] = in[i];
    for (int i = 0; i < 3; ++i) s.Pi(i) = in[9 + i];
  }
};

/// T³ × ℝ³ (the Cardan top): the unwrapped angles q, then the momenta p.
template <>
struct StateSpace<system::TorusState> {
  static constexpr const char* name = "T^3 x R^3";
  static constexpr std::size_t dimension = 6;
  static bool finite(const system::TorusState& s) {
    double z = 0.0;
    for (int i = 0; i < 3; ++i) z += (s.q(i) - s.q(i)) + (s.p(i) - s.p(i));
    return z == 0.0;
  }
  static void write(const system::TorusState& s, double* out) {
    for (int i = 0; i < 3; ++i) out[i] = s.q(i), out[3 + i] = s.p(i);
  }
  static void read(const double* in, system::TorusState& s) {
    for (int i = 0; i < 3; ++i) s.q(i) = in[i], s.p(i) = in[3 + i];
  }
};

namespace detail {
template <class Model>
struct model_state {
  using type = system::State;
};
template <class Model>
  requires requires { typename Model::state_type; }
struct model_state<Model> {
  using type = typename Model::state_type;
};
}  // namespace detail

/// The state type a model's runs carry.
template <class Model>
using state_of = typename detail::model_state<Model>::type;

}  // namespace lgi::integrators

#pragma once
// Numbers of several lanes for the ensemble kernels (docs/ensemble.md).
//
// A kernel is written once for a number type T: double (one trajectory) or
// Lanes<Batch, K>, K xsimd batches of B doubles each, K·B trajectories. Every
// operation of Lanes is the IEEE operation applied lane by lane (+ − × ÷ and
// √ are correctly rounded at any vector width, and this code is compiled
// with -ffp-contract=off: no fused multiply-add), so lane j computes exactly
// what the double version computes for trajectory j. The K batches are
// independent chains that the CPU overlaps: one trajectory's step is a
// chain of dependent operations, bound by latency rather than throughput.
//
// Transcendentals never use xsimd's own: cos_sin_unless() calls the scalar
// libm functions lane by lane, so a lane gets the very bits std::sin gives the
// scalar scheme (the Cardan kernel, whose scalar step is new, writes its cos
// and sin in lane_sincos.hpp instead). Branches on a lane's value become select() of both sides,
// with the costly side computed only where some lane needs it.
//
// This header is included by translation units compiled for one instruction
// set each (ensemble_avx2.cpp, ...): everything here is a template on the
// lane type, so no function compiled for a wider instruction set can be
// chosen by the linker for another unit (no shared inline definitions).
#include <xsimd/xsimd.hpp>

#include <cmath>
#include <cstddef>

namespace lgi::integrators::ensemble {

template <class Batch, int K>
struct Lanes {
  using batch_type = Batch;
  using mask_type = typename Batch::batch_bool_type;
  static constexpr int batches = K;
  static constexpr int size = K * static_cast<int>(Batch::size);
  Batch b[static_cast<std::size_t>(K)];

  Lanes() = default;
  Lanes(double x) {  // NOLINT: a constant is the same in every lane
    for (int k = 0; k < K; ++k) b[k] = Batch(x);
  }
};

template <class Batch, int K>
struct LaneMask {
  typename Batch::batch_bool_type b[static_cast<std::size_t>(K)];
};

#define LGI_LANES_BINARY(op)                                                           \
  template <class B, int K>                                                            \
  inline Lanes<B, K> operator op(const Lanes<B, K>& x, const Lanes<B, K>& y) {         \
    Lanes<B, K> r;                                                                     \
    for (int k = 0; k < K; ++k) r.b[k] = x.b[k] op y.b[k];                             \
    return r;                                                                          \
  }                                                                                    \
  template <class B, int K>                                                            \
  inline Lanes<B, K> operator op(const Lanes<B, K>& x, double y) {                     \
    Lanes<B, K> r;                                                                     \
    for (int k = 0; k < K; ++k) r.b[k] = x.b[k] op B(y);                               \
    return r;                                                                          \
  }                                                                                    \
  template <class B, int K>                                                            \
  inline Lanes<B, K> operator op(double x, const Lanes<B, K>& y) {                     \
    Lanes<B, K> r;                                                                     \
    for (int k = 0; k < K; ++k) r.b[k] = B(x) op y.b[k];                               \
    return r;                                                                          \
  }
LGI_LANES_BINARY(+)
LGI_LANES_BINARY(-)
LGI_LANES_BINARY(*)
LGI_LANES_BINARY(/)
#undef LGI_LANES_BINARY

/// −x flips the sign bit, as the scalar negation does.
template <class B, int K>
inline Lanes<B, K> operator-(const Lanes<B, K>& x) {
  Lanes<B, K> r;
  for (int k = 0; k < K; ++k) r.b[k] = -x.b[k];
  return r;
}

template <class B, int K>
inline Lanes<B, K> sqrt(const Lanes<B, K>& x) {
  Lanes<B, K> r;
  for (int k = 0; k < K; ++k) r.b[k] = xsimd::sqrt(x.b[k]);
  return r;
}
inline double sqrt(double x) { return __builtin_sqrt(x); }

/// Comparisons lane by lane, with another lane number or a constant (false
/// for NaN, as in the scalar comparisons): less, less_equal, greater, equal.
#define LGI_LANES_COMPARE(name, op)                                                  \
  template <class B, int K>                                                          \
  inline LaneMask<B, K> name(const Lanes<B, K>& x, const Lanes<B, K>& y) {           \
    LaneMask<B, K> m;                                                                \
    for (int k = 0; k < K; ++k) m.b[k] = x.b[k] op y.b[k];                           \
    return m;                                                                        \
  }                                                                                  \
  template <class B, int K>                                                          \
  inline LaneMask<B, K> name(const Lanes<B, K>& x, double c) {                       \
    return name(x, Lanes<B, K>(c));                                                  \
  }
LGI_LANES_COMPARE(less, <)
LGI_LANES_COMPARE(less_equal, <=)
LGI_LANES_COMPARE(greater, >)
LGI_LANES_COMPARE(equal, ==)
#undef LGI_LANES_COMPARE
inline bool less(double x, double c) { return x < c; }

/// Both masks (&), either mask (|).
#define LGI_LANES_MASK(op, logical)                                                  \
  template <class B, int K>                                                          \
  inline LaneMask<B, K> operator op(const LaneMask<B, K>& x, const LaneMask<B, K>& y) { \
    LaneMask<B, K> m;                                                                \
    for (int k = 0; k < K; ++k) m.b[k] = x.b[k] logical y.b[k];                      \
    return m;                                                                        \
  }
LGI_LANES_MASK(&, &&)
LGI_LANES_MASK(|, ||)
#undef LGI_LANES_MASK

/// |x| lane by lane (clears the sign bit, as std::abs does).
template <class B, int K>
inline Lanes<B, K> abs(const Lanes<B, K>& x) {
  Lanes<B, K> r;
  for (int k = 0; k < K; ++k) r.b[k] = xsimd::abs(x.b[k]);
  return r;
}

/// m ? a : b lane by lane.
template <class B, int K>
inline Lanes<B, K> select(const LaneMask<B, K>& m, const Lanes<B, K>& a, const Lanes<B, K>& b) {
  Lanes<B, K> r;
  for (int k = 0; k < K; ++k) r.b[k] = xsimd::select(m.b[k], a.b[k], b.b[k]);
  return r;
}
inline double select(bool m, double a, double b) { return m ? a : b; }

template <class B, int K>
inline bool all(const LaneMask<B, K>& m) {
  for (int k = 0; k < K; ++k)
    if (!xsimd::all(m.b[k])) return false;
  return true;
}
inline bool all(bool m) { return m; }

template <class B, int K>
inline bool any(const LaneMask<B, K>& m) {
  for (int k = 0; k < K; ++k)
    if (xsimd::any(m.b[k])) return true;
  return false;
}
inline bool any(bool m) { return m; }

template <class B, int K>
inline Lanes<B, K> load(const double* p) {
  Lanes<B, K> r;
  for (int k = 0; k < K; ++k) r.b[k] = B::load_aligned(p + k * static_cast<int>(B::size));
  return r;
}
template <class B, int K>
inline void store(const Lanes<B, K>& x, double* p) {
  for (int k = 0; k < K; ++k) x.b[k].store_aligned(p + k * static_cast<int>(B::size));
}

/// f(x_j, y_j, z_j) for each lane j where `skip` is false; y and z are 0 in the others.
template <class B, int K, class F>
inline void for_lanes_unless(const LaneMask<B, K>& skip, const Lanes<B, K>& x, Lanes<B, K>& y, Lanes<B, K>& z,
                             F&& f) {
  constexpr int n = Lanes<B, K>::size;
  constexpr int width = static_cast<int>(B::size);
  constexpr auto size = static_cast<std::size_t>(n);
  alignas(64) double in[size];
  alignas(64) double out_y[size] = {};
  alignas(64) double out_z[size] = {};
  alignas(64) bool skipped[size];
  store(x, in);
  for (int k = 0; k < K; ++k) skip.b[k].store_aligned(skipped + k * width);
  bool none = true;
  for (int k = 0; k < K; ++k) none = none && !xsimd::any(skip.b[k]);
  if (none) {  // the usual case: no branch per lane
    for (int j = 0; j < n; ++j) f(in[j], out_y[j], out_z[j]);
  } else {
    for (int j = 0; j < n; ++j)
      if (!skipped[j]) f(in[j], out_y[j], out_z[j]);
  }
  y = load<B, K>(out_y);
  z = load<B, K>(out_z);
}

/// cos x and sin x in the lanes where `skip` is false, computed together as
/// the scalar code computes them (which the compiler may fuse into one
/// sincos call, there and here alike).
template <class B, int K>
inline void cos_sin_unless(const LaneMask<B, K>& skip, const Lanes<B, K>& x, Lanes<B, K>& c, Lanes<B, K>& s) {
  for_lanes_unless(skip, x, c, s, [](double in, double& co, double& si) {
    co = std::cos(in);
    si = std::sin(in);
  });
}
inline void cos_sin_unless(bool skip, double x, double& c, double& s) {
  c = skip ? 0.0 : std::cos(x);
  s = skip ? 0.0 : std::sin(x);
}

}  // namespace lgi::integrators::ensemble

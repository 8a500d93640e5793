// The ensemble kernels for AVX-512F (8 doubles per batch), 2 batches
// interleaved: 16 lanes. Compiled with -mavx512f (integrators/CMakeLists.txt)
// and -ffp-contract=off, so that although the instruction set has fused
// multiply-adds, none is emitted; called only where the CPU has AVX-512F.
// GCC 12's avx512fintrin.h initialises _mm512_undefined_pd() from itself
// (`__m512d __Y = __Y;`, deliberately undefined), which -Wuninitialized
// reports wherever an intrinsic using it (_mm512_sqrt_pd) is inlined (as
// -Wmaybe-uninitialized where that inlining sits behind a branch).
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "integrators/ensemble/cardan_tangent_kernel.hpp"
#include "integrators/ensemble/kernel_set.hpp"

namespace lgi::integrators::ensemble {

KernelSet avx512_kernels() { return kernel_set<Lanes<xsimd::batch<double, xsimd::avx512f>, 2>>("avx512"); }

TangentKernelSet avx512_tangent_kernels() { return tangent_kernel_set<Lanes<xsimd::batch<double, xsimd::avx512f>, 2>>(); }

CardanTangentKernelSet avx512_cardan_tangent_kernels() {
  return cardan_tangent_kernel_set<Lanes<xsimd::batch<double, xsimd::avx512f>, 2>>();
}

}  // namespace lgi::integrators::ensemble

// The ensemble kernels for AVX2 (4 doubles per batch), 2 batches interleaved:
// 8 lanes. Compiled with -mavx2 and without -mfma (integrators/CMakeLists.txt),
// called only where the CPU has AVX2 (ensemble.cpp).
#include "integrators/ensemble/cardan_tangent_kernel.hpp"
#include "integrators/ensemble/kernel_set.hpp"

namespace lgi::integrators::ensemble {

KernelSet avx2_kernels() { return kernel_set<Lanes<xsimd::batch<double, xsimd::avx2>, 2>>("avx2"); }

TangentKernelSet avx2_tangent_kernels() { return tangent_kernel_set<Lanes<xsimd::batch<double, xsimd::avx2>, 2>>(); }

CardanTangentKernelSet avx2_cardan_tangent_kernels() {
  return cardan_tangent_kernel_set<Lanes<xsimd::batch<double, xsimd::avx2>, 2>>();
}

}  // namespace lgi::integrators::ensemble

// The ensemble kernels for the baseline instruction set of the build (SSE2
// on x86-64: 2 doubles per batch), 4 batches interleaved: 8 lanes.
#include "integrators/ensemble/cardan_tangent_kernel.hpp"
#include "integrators/ensemble/kernel_set.hpp"

namespace lgi::integrators::ensemble {

KernelSet baseline_kernels() {
  using Arch = xsimd::default_arch;
  return kernel_set<Lanes<xsimd::batch<double, Arch>, 8 / static_cast<int>(xsimd::batch<double, Arch>::size)>>(
      Arch::name());
}

TangentKernelSet baseline_tangent_kernels() {
  using Arch = xsimd::default_arch;
  return tangent_kernel_set<Lanes<xsimd::batch<double, Arch>, 8 / static_cast<int>(xsimd::batch<double, Arch>::size)>>();
}

CardanTangentKernelSet baseline_cardan_tangent_kernels() {
  using Arch = xsimd::default_arch;
  return cardan_tangent_kernel_set<
      Lanes<xsimd::batch<double, Arch>, 8 / static_cast<int>(xsimd::batch<double, Arch>::size)>>();
}

}  // namespace lgi::integrators::ensemble

#include "experiments/io/libm_code_path.hpp"

#if defined(__GLIBC__)
#include <gnu/libc-version.h>
#if defined(__x86_64__) && defined(__has_include)
#if __has_include(<sys/platform/x86.h>)
#if defined(__clang__)  // the header is C (it returns _Bool), which GCC accepts in C++ and clang does not
#define _Bool bool
#endif
#include <sys/platform/x86.h>  // glibc ≥ 2.33: the features glibc itself treats as usable
#if defined(__clang__)
#undef _Bool
#endif
#define LGI_GLIBC_X86_FEATURES 1
#endif
#endif
#endif

namespace lgi::experiments {

std::string libm_code_path() {
#if defined(__GLIBC__)
  std::string out = std::string("glibc ") + gnu_get_libc_version();
#if defined(LGI_GLIBC_X86_FEATURES)
  // glibc's selector for these functions (sysdeps/x86_64/fpu/multiarch/
  // ifunc-fma4.h and ifunc-avx-fma4.h, glibc 2.36): FMA with AVX2 first, then
  // FMA4, else SSE2 or AVX, whose results are the same (no contraction).
  // CPU_FEATURE_ACTIVE reads the usable features after GLIBC_TUNABLES.
  if (CPU_FEATURE_ACTIVE(FMA) && CPU_FEATURE_ACTIVE(AVX2)) return out + ", FMA code paths";
  if (CPU_FEATURE_ACTIVE(FMA4)) return out + ", FMA4 code paths";
  return out + ", non-FMA code paths";
#else
  return out;
#endif
#else
  return "not glibc";
#endif
}

}  // namespace lgi::experiments

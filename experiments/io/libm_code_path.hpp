#pragma once
// Which code path the C library's maths functions take on this machine: the
// `libm` attribute of every output file (experiments/OUTPUT.md, README
// "Numerics policy"). On x86-64, glibc picks one of several builds of sin, cos,
// tan, atan, atan2, asin, acos, exp, log and pow when the program starts, by
// the CPU's features: one compiled with FMA (when FMA and AVX2 are usable),
// one with FMA4, or one without. They are not correctly rounded, and they
// round differently: about 1 result in 1400 differs by 1 ulp between the FMA
// and the non-FMA build (glibc 2.36, 10⁶ random arguments each). A run that
// calls them (a pair's step-size controller, the exact free flow, a large
// angle in exp) is then the same bits on two machines only if both take the
// same path. GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA,-FMA4 makes every
// x86-64 machine take the non-FMA one.
#include <string>

namespace lgi::experiments {

/// "glibc 2.36, FMA code paths", "… FMA4 code paths" or "… non-FMA code
/// paths" (the glibc build's own choice, GLIBC_TUNABLES included); "glibc
/// 2.36" where the choice cannot be read; "not glibc" elsewhere.
std::string libm_code_path();

}  // namespace lgi::experiments

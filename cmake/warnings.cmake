# Warnings for project code only (never applied to the dependencies' headers,
# which are included as SYSTEM through their imported targets).
add_library(lgi_warnings INTERFACE)
set_target_properties(lgi_warnings PROPERTIES EXPORT_NAME warnings)
target_compile_options(lgi_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion)

# Floating-point policy: IEEE semantics everywhere. -ffp-contract=off keeps
# the compiler from fusing a*b+c into an FMA, so conservation studies see the
# rounding the source describes on every machine. -ffast-math is never used.
# LGI_FP_CONTRACT=fast (the opt-in release-native preset, with -march=native)
# lets the compiler fuse: still IEEE arithmetic, but results then depend on
# the machine and differ from the default build at round-off; the flag is
# recorded in every output file (cmake/provenance.cmake).
set(LGI_FP_CONTRACT "off" CACHE STRING "-ffp-contract= value: off (default, reproducible) or fast (opt-in)")
set_property(CACHE LGI_FP_CONTRACT PROPERTY STRINGS off fast)
if(NOT LGI_FP_CONTRACT MATCHES "^(off|fast)$")
  message(FATAL_ERROR "LGI_FP_CONTRACT must be off or fast, not '${LGI_FP_CONTRACT}'")
endif()
add_library(lgi_fp_policy INTERFACE)
set_target_properties(lgi_fp_policy PROPERTIES EXPORT_NAME fp_policy)
target_compile_options(lgi_fp_policy INTERFACE -ffp-contract=${LGI_FP_CONTRACT} -fno-fast-math)

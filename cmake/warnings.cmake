# Warnings for project code only (never applied to the dependencies' headers,
# which are included as SYSTEM through their imported targets).
add_library(lgi_warnings INTERFACE)
set_target_properties(lgi_warnings PROPERTIES EXPORT_NAME warnings)
target_compile_options(lgi_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion)

# Floating-point policy: IEEE semantics everywhere. -ffp-contract=off keeps
# the compiler from fusing a*b+c into an FMA, so conservation studies see the
# rounding the source describes on every machine. -ffast-math is never used.
add_library(lgi_fp_policy INTERFACE)
set_target_properties(lgi_fp_policy PROPERTIES EXPORT_NAME fp_policy)
target_compile_options(lgi_fp_policy INTERFACE -ffp-contract=off -fno-fast-math)

#pragma once
// LGI_FLATTEN: [[gnu::flatten]] on the functions that run a step's stages
// (rkmk.hpp, rkmk_pair.hpp), so that the compiler inlines every call in them
// and schedules the stages as one block (docs/performance.md §2). Off under
// AddressSanitizer (the sanitize and fuzz presets): there the fully inlined,
// instrumented stage functions took over 20 minutes to compile one unit, and
// speed is not what those builds are for. Inlining changes no result.
#if defined(__SANITIZE_ADDRESS__)
#define LGI_FLATTEN
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define LGI_FLATTEN
#endif
#endif
#ifndef LGI_FLATTEN
#define LGI_FLATTEN [[gnu::flatten]]
#endif

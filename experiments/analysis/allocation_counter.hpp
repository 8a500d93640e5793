#pragma once
// Counts the program's heap allocations for the verification kit's
// "no allocation per step" check (scheme_verification.hpp), by replacing the
// global operator new and delete. Include this header in exactly ONE
// translation unit of a program (a second one breaks the link: the
// replacements are ordinary definitions), then pass
//   options.allocation_count = &lgi::experiments::verification::counted_allocations;
// Every replaceable form that is not over-aligned is replaced, so that
// allocation and release always pair malloc with free (AddressSanitizer
// checks the pairing).
#include <atomic>
#include <cstdlib>
#include <new>

namespace lgi::experiments::verification {

inline std::atomic<long> allocation_counter{0};

inline long counted_allocations() { return allocation_counter.load(std::memory_order_relaxed); }

namespace detail_allocation {
inline void* counted_malloc(std::size_t n) noexcept {
  allocation_counter.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(n ? n : 1);
}
inline void* counted_or_throw(std::size_t n) {
  if (void* p = counted_malloc(n)) return p;
  throw std::bad_alloc();
}
}  // namespace detail_allocation

}  // namespace lgi::experiments::verification

void* operator new(std::size_t n) { return lgi::experiments::verification::detail_allocation::counted_or_throw(n); }
void* operator new[](std::size_t n) { return lgi::experiments::verification::detail_allocation::counted_or_throw(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  return lgi::experiments::verification::detail_allocation::counted_malloc(n);
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  return lgi::experiments::verification::detail_allocation::counted_malloc(n);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

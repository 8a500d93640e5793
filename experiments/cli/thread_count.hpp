#pragma once
// The --threads bound of the commands that run OpenMP teams (README.md,
// "Limits"): a whole number from 1 to 64 threads per hardware core. More
// threads than that only crowd the cores, and 10^5 of them end libgomp in a
// crash (issue 50); the check happens before any work.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <string>
#include <thread>

namespace lgi::experiments {

inline constexpr int threads_per_core_limit = 64;

/// 64 x std::thread::hardware_concurrency() (64 if the count is unknown).
inline int max_threads() {
  return threads_per_core_limit * static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

/// CLI11 check of --threads; its message becomes "--threads: ..." on one line.
inline CLI::Validator thread_count_check() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        long long n = 0;
        const auto r = std::from_chars(text.data(), text.data() + text.size(), n);
        const int limit = max_threads();
        if (r.ec == std::errc() && r.ptr == text.data() + text.size() && n >= 1 && n <= limit) return {};
        return "'" + text + "' is not a thread count from 1 to " + std::to_string(limit) + " (" +
               std::to_string(threads_per_core_limit) + " per hardware core)";
      },
      "1..64 per core", "thread_count");
}

}  // namespace lgi::experiments

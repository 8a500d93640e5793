#pragma once
// Progress of a sweep on stderr (experiments/SWEEPS.md, "Progress"): on a
// terminal one line updated in place at most 5 times a second; off a
// terminal a line every 10 s; nothing with --quiet. Trajectories done out of
// the total, the rate of this run, the time left and the failures so far.
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>

namespace lgi::experiments {

class SweepProgress {
 public:
  /// `done_before`: trajectories completed by an earlier run (--resume). `command` and `unit` name
  /// the line's command and what it counts (lgi chaos-map: "chaos-map", "orbits").
  SweepProgress(bool quiet, std::int64_t total, std::int64_t done_before, const char* command = "sweep",
                const char* unit = "trajectories")
      : command_(command),
        unit_(unit),
        enabled_(!quiet),
        terminal_(::isatty(STDERR_FILENO) == 1),
        total_(total),
        before_(done_before),
        start_(std::chrono::steady_clock::now()),
        last_(start_) {}

  void update(std::int64_t done, std::int64_t failures) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    const double since = std::chrono::duration<double>(now - last_).count();
    if (since < (terminal_ ? 0.2 : 10.0) && done < total_) return;
    last_ = now;
    print(done, failures, now, terminal_ ? "\r\033[K" : "", terminal_ ? "" : "\n");
    shown_ = true;
  }
  /// Ends the in-place line.
  void finish() {
    if (enabled_ && shown_ && terminal_) std::fputs("\n", stderr);
  }

 private:
  void print(std::int64_t done, std::int64_t failures, std::chrono::steady_clock::time_point now, const char* lead,
             const char* tail) const {
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double rate = elapsed > 0.0 ? static_cast<double>(done - before_) / elapsed : 0.0;
    const double left = rate > 0.0 ? static_cast<double>(total_ - done) / rate : 0.0;
    std::fprintf(stderr, "%s%s: %lld/%lld %s, %.3g/s, %s left, %lld failed%s", lead, command_,
                 static_cast<long long>(done), static_cast<long long>(total_), unit_, rate, duration(left).c_str(),
                 static_cast<long long>(failures), tail);
    std::fflush(stderr);
  }
  static std::string duration(double s) {
    char buf[32];
    if (s < 60) std::snprintf(buf, sizeof buf, "%.0f s", s);
    else if (s < 3600) std::snprintf(buf, sizeof buf, "%d min %02d s", static_cast<int>(s / 60), static_cast<int>(s) % 60);
    else std::snprintf(buf, sizeof buf, "%d h %02d min", static_cast<int>(s / 3600), static_cast<int>(s / 60) % 60);
    return buf;
  }
  const char *command_, *unit_;
  bool enabled_, terminal_, shown_ = false;
  std::int64_t total_, before_;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace lgi::experiments

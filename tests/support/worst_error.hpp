#pragma once
// The worst value of an error measure over a test case, printed at the end of
// the test case when LGI_TEST_REPORT is set (so a run can list how close each
// check came to its bound).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <utility>

namespace lgi::testing {

class Worst {
 public:
  explicit Worst(std::string name) : name_(std::move(name)) {}
  Worst(const Worst&) = delete;
  Worst& operator=(const Worst&) = delete;
  ~Worst() {
    if (std::getenv("LGI_TEST_REPORT") != nullptr) {
      std::printf("[worst] %-62s %.3e  (%s)\n", name_.c_str(), worst_, where_.c_str());
    }
  }
  double operator()(double err, const std::string& where) {
    const double e = std::isnan(err) ? std::numeric_limits<double>::infinity() : err;
    if (!seen_ || e > worst_) {
      seen_ = true;
      worst_ = e;
      where_ = where;
    }
    return err;
  }

 private:
  std::string name_;
  bool seen_ = false;
  double worst_ = 0.0;
  std::string where_;
};

}  // namespace lgi::testing

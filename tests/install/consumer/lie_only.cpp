// lgi::lie alone (header-only, Eigen only): exp and log on SO(3) round-trip.
#include <cstdio>

#include "lie/so3.hpp"

int main() {
  const lgi::lie::Vec3 xi(0.3, -0.2, 0.1);
  const double err = (lgi::lie::log_so3(lgi::lie::exp_so3(xi)) - xi).norm();
  std::printf("log(exp(xi)) - xi = %.3e\n", err);
  return err < 1e-15 ? 0 : 1;
}

#pragma once
// Entry-wise closeness of 3×3 matrices and 3-vectors: the largest absolute
// difference is at most tol.
#include "lie/so3.hpp"

namespace lgi::testing {

inline bool near(const lie::Mat3& a, const lie::Mat3& b, double tol) { return (a - b).cwiseAbs().maxCoeff() <= tol; }
inline bool near(const lie::Vec3& a, const lie::Vec3& b, double tol) { return (a - b).cwiseAbs().maxCoeff() <= tol; }

}  // namespace lgi::testing

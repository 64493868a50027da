// Shared by the reader and the importers (private to wedge_recordings): the one rule for orientations.
#pragma once

#include <Eigen/Geometry>
#include <cmath>

namespace wedge::recordings {

// How far a quaternion's norm may be from 1 and still be taken as a rotation: recorders print 6 to 7
// significant digits, so their unit quaternions are off by ~1e-6; anything past 1e-3 is a wrong column.
inline constexpr double kUnitQuaternionTolerance = 1e-3;

// False if |q| differs from 1 by more than kUnitQuaternionTolerance. Otherwise normalises q, unless it is
// already unit to round-off: normalising is not idempotent in the last bit, and leaving such a quaternion
// alone is what makes read(write(r)) == r bit for bit.
inline bool accept_unit_quaternion(Eigen::Quaterniond& q, double& norm) {
  norm = q.norm();
  if (!(std::abs(norm - 1.0) <= kUnitQuaternionTolerance)) return false;  // NaN fails too
  if (std::abs(norm - 1.0) > 1e-12) q.coeffs() /= norm;
  return true;
}

}  // namespace wedge::recordings

// Rigid poses in double precision, the runtime's working form of XrPosef: a position and a unit quaternion
// taking the local frame to the parent frame (x' = q x + p). Everything is computed in double and rounded to
// float only when written into an OpenXR struct.
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "xr_platform.hpp"

namespace wedge::xr_replay {

struct Pose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

// a * b: b expressed in a's parent frame (first b, then a).
inline Pose compose(const Pose& a, const Pose& b) {
  return {a.position + a.orientation * b.position, (a.orientation * b.orientation).normalized()};
}

inline Pose inverse(const Pose& a) {
  const Eigen::Quaterniond qi = a.orientation.conjugate();
  return {-(qi * a.position), qi};
}

inline Pose from_xr(const XrPosef& p) {
  return {Eigen::Vector3d(p.position.x, p.position.y, p.position.z),
          Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z).normalized()};
}

inline XrPosef to_xr(const Pose& p) {
  XrPosef out;
  out.position = {float(p.position.x()), float(p.position.y()), float(p.position.z())};
  out.orientation = {float(p.orientation.x()), float(p.orientation.y()), float(p.orientation.z()),
                     float(p.orientation.w())};
  return out;
}

// The spec's test for a pose an app hands in: finite, and a quaternion of unit length (within 1 %, which
// float round-off and hand-typed constants stay well inside). Else XR_ERROR_POSE_INVALID.
inline bool is_valid_pose(const XrPosef& p) {
  const double v[7] = {p.position.x, p.position.y, p.position.z, p.orientation.x, p.orientation.y, p.orientation.z,
                       p.orientation.w};
  for (double x : v)
    if (!std::isfinite(x)) return false;
  const double n2 = v[3] * v[3] + v[4] * v[4] + v[5] * v[5] + v[6] * v[6];
  return std::abs(n2 - 1.0) <= 0.02;
}

}  // namespace wedge::xr_replay

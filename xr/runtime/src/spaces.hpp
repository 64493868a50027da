// Where a space is, in the tracking space (the one space STAGE and LOCAL both are: identity between them,
// y up, the recording's frame), at any XrTime: the recording is sampled at exactly that time, so sub-frame
// times are answered as precisely as frame times.
#pragma once

#include "objects.hpp"

namespace wedge::xr_replay {

// The aim pose in the grip pose's frame: 5 cm forward along the controller's -z, turned 30 degrees down
// about its x axis (docs/xr-runtime.md).
Pose aim_in_grip();

struct Located {
  bool valid = false;  // position and orientation both valid and tracked
  Pose pose;
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();   // of the space's origin, tracking frame
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
};

Located locate(const Space& space, XrTime t);
const char* space_type_name(const Space& space);  // "VIEW", "LOCAL", "STAGE", "ACTION"

}  // namespace wedge::xr_replay

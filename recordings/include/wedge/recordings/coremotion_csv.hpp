// iPhone CoreMotion device-motion recordings (CSV with a header row, columns in any order, as exported
// from CoreMotion's CMDeviceMotion): the columns the input layer uses, in CoreMotion's units and device
// frame. Raw accelerometer = user_acceleration + gravity (CoreMotion's convention).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace wedge::recordings {

struct CoreMotionSample {
  double time = 0.0;                                       // s, `timestamp`
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();       // g, `gravity.{x,y,z}`: CoreMotion's own estimate
  Eigen::Vector3d user_acceleration = Eigen::Vector3d::Zero();  // g, gravity removed
  Eigen::Vector3d rotation_rate = Eigen::Vector3d::Zero();      // rad/s, device frame
};

// Reads a whole file, in any RFC 4180 dialect (csv_table.hpp). Throws wedge::Error naming the file, and the
// line where there is one ("PATH:LINE: problem"), for malformed quoting, a missing
// file or column, a field that is not a finite number, a short row, or timestamps that go backwards.
std::vector<CoreMotionSample> read_coremotion_csv(const std::string& path);

}  // namespace wedge::recordings

// What a device reports, as timed samples: a hand controller's pose, grip, trigger and buttons, a head's
// pose, a phone's accelerometer and gyro. The input layer consumes them (frame.hpp); recordings/ writes and
// reads them as files (docs/recording-format.md); the OpenXR app (xr/) fills them from a runtime.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>

namespace wedge::input {

enum class Hand : std::uint8_t { Left = 0, Right = 1 };

// Buttons: the Oculus SDK TouchButtons bits (A = 0x1, B = 0x2, X = 0x100, Y = 0x200); other bits are not kept.
inline constexpr std::uint32_t kButtonA = 0x1, kButtonB = 0x2, kButtonX = 0x100, kButtonY = 0x200;

struct Pose {  // tracking space: metres, OpenXR convention (x right, y up, z toward the user)
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // unit; local -> tracking
};

struct HandSample {
  double t = 0.0;  // s on the device's clock (recordings start it at 0)
  Hand hand = Hand::Right;
  Pose pose;                  // the controller's grip pose
  double squeeze = 0.0;       // [0, 1] grip ("hand trigger")
  double trigger = 0.0;       // [0, 1] index trigger
  std::uint32_t buttons = 0;  // kButton* bits
  bool mode4d = false;        // the device's own 4D-rotation flag (besides A / X)
};

struct HeadSample {
  double t = 0.0;
  Pose pose;
};

struct MotionSample {
  double t = 0.0;
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();  // g, device frame (x right, y up, z out of the screen),
                                   // gravity included and pointing the way it pulls (CoreMotion's sign: a
                                   // still phone held upright reads (0, -1, 0))
  bool has_rotation_rate = false;
  Eigen::Vector3d rotation_rate = Eigen::Vector3d::Zero();  // rad/s, device frame
  bool tilt = false;  // the paper's gravity-tilt button (tilt toward w)
};

}  // namespace wedge::input

// What the input layer reads before one step: each hand's state at the step's time, in tracking space,
// and the motion (accelerometer) samples that arrived since the last step. Device-agnostic: the OpenXR
// app, the desktop viewer and the recording replay (wedge/recordings/recording_source.hpp) all fill this.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <span>

#include "wedge/input/samples.hpp"

namespace wedge::input {

inline constexpr int kHandCount = 2;  // indexed by int(Hand): 0 left, 1 right

struct HandInput {
  bool tracked = false;  // false: no pose known yet (the hand does nothing)
  Eigen::Vector3d position = Eigen::Vector3d::Zero();                // m, tracking space (OpenXR: y up)
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // controller -> tracking
  double squeeze = 0.0;   // [0, 1]: grabs past InteractionSettings::squeeze_on
  double trigger = 0.0;   // [0, 1]: recorded, not used by the physics
  std::uint32_t buttons = 0;  // kButton* bits (recorded; the physics reads mode4d)
  bool mode4d = false;    // 4D rotation mode held (A on the right controller, X on the left, or a flag)
};

struct InputFrame {
  double t = 0.0;  // s: the step's time (step index * h)
  std::array<HandInput, kHandCount> hands;
  // Accelerometer samples with time in (previous frame's t, t], in order (may be empty).
  std::span<const MotionSample> motion;
};

}  // namespace wedge::input

// Gravity as a phone feels it, for tilting the world's gravity (paper section 8): the direction of gravity
// in the device frame, from the accelerometer (gravity plus the hand's own acceleration) and the gyro.
//
// A complementary filter: each sample first turns the estimate with the device (a fixed direction seen
// from a frame spinning at w turns at -w: dg/dt = g x w, integrated exactly for constant w over the
// sample), then pulls it toward the measured acceleration with time constant tau. The gyro carries fast
// turns; the accelerometer, averaged over tau, removes the gyro's drift and ignores the hand's shaking.
// Measured on a real hand-held iPhone trace (recordings/coremotion/kinetic_tremor_data.csv): 4.0 degrees
// from CoreMotion's own fused gravity at the median with tau = 5 s, where the accelerometer alone, low-
// passed at any tau, is 15 degrees off (tests/input/test_gravity_filter.cpp).
#pragma once

#include <Eigen/Core>

namespace wedge::input {

struct GravityFilterSettings {
  double time_constant = 5.0;  // s: how slowly the accelerometer corrects the gyro-propagated estimate
};

class GravityFilter {
 public:
  // Throws wedge::Error unless the time constant is finite and > 0.
  explicit GravityFilter(const GravityFilterSettings& settings = {});

  // One sample: acceleration (any unit, e.g. g; gravity included, pointing the way gravity pulls as in
  // CoreMotion, device frame), rotation rate (rad/s, device frame), dt (s) since the previous sample. The
  // first sample sets the estimate. Throws wedge::Error for non-finite values or dt < 0.
  void update(const Eigen::Vector3d& acceleration, const Eigen::Vector3d& rotation_rate, double dt);

  bool ready() const { return ready_; }
  // The estimate, in the acceleration's unit (about 1 g at rest), device frame.
  const Eigen::Vector3d& gravity() const { return gravity_; }
  // Its direction (unit); (0, 0, 0) before the first sample or for a zero estimate.
  Eigen::Vector3d direction() const;

 private:
  GravityFilterSettings settings_;
  Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();
  bool ready_ = false;
};

}  // namespace wedge::input

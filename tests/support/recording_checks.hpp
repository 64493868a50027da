// Comparing recordings bit for bit (the format promises read(write(r)) == r), for the recording tests.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>

#include "wedge/recordings/recording.hpp"

namespace recording_checks {

using namespace wedge::recordings;

inline bool same_bits(double a, double b) {  // unlike ==, tells -0.0 from 0.0
  std::uint64_t x = 0, y = 0;
  std::memcpy(&x, &a, sizeof x);
  std::memcpy(&y, &b, sizeof y);
  return x == y;
}
inline bool same_bits(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return same_bits(a.x(), b.x()) && same_bits(a.y(), b.y()) && same_bits(a.z(), b.z());
}
inline bool same_bits(const Pose& a, const Pose& b) {
  return same_bits(a.position, b.position) && same_bits(a.orientation.w(), b.orientation.w()) &&
         same_bits(a.orientation.vec(), b.orientation.vec());
}

// "" if the two recordings hold the same samples bit for bit (warnings aside), else the first difference.
inline std::string first_difference(const Recording& a, const Recording& b) {
  if (a.source != b.source) return "source '" + a.source + "' vs '" + b.source + "'";
  if (a.hands.size() != b.hands.size()) return "hands: " + std::to_string(a.hands.size()) + " vs " +
                                              std::to_string(b.hands.size()) + " samples";
  if (a.heads.size() != b.heads.size()) return "heads: sizes differ";
  if (a.motion.size() != b.motion.size()) return "motion: sizes differ";
  for (std::size_t i = 0; i < a.hands.size(); ++i) {
    const HandSample &x = a.hands[i], &y = b.hands[i];
    if (!same_bits(x.t, y.t) || x.hand != y.hand || !same_bits(x.pose, y.pose) || !same_bits(x.squeeze, y.squeeze) ||
        !same_bits(x.trigger, y.trigger) || x.buttons != y.buttons || x.mode4d != y.mode4d)
      return "hands[" + std::to_string(i) + "]";
  }
  for (std::size_t i = 0; i < a.heads.size(); ++i)
    if (!same_bits(a.heads[i].t, b.heads[i].t) || !same_bits(a.heads[i].pose, b.heads[i].pose))
      return "heads[" + std::to_string(i) + "]";
  for (std::size_t i = 0; i < a.motion.size(); ++i) {
    const MotionSample &x = a.motion[i], &y = b.motion[i];
    if (!same_bits(x.t, y.t) || !same_bits(x.acceleration, y.acceleration) ||
        x.has_rotation_rate != y.has_rotation_rate || !same_bits(x.rotation_rate, y.rotation_rate) || x.tilt != y.tilt)
      return "motion[" + std::to_string(i) + "]";
  }
  return "";
}

}  // namespace recording_checks

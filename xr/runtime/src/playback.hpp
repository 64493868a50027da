// The recording, sampled at any XrTime (docs/xr-runtime.md, "Recording"). The rule is Wedge's own
// (input/src/recording_source.cpp), on integer nanoseconds: at time T a hand uses its last sample at or
// before T, blended with the next one when they are at most kInterpolationGap apart (position linearly,
// orientation by slerp), else held; before its first sample the hand is untracked. Buttons and analog
// values are the last sample's, never blended. Head samples, when there are any, give the view pose the
// same way (before the first one, the first one is held); without them the head is default_head().
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "clock.hpp"
#include "pose.hpp"

namespace wedge::recordings {
struct Recording;
}

namespace wedge::xr_replay {

// The recording's tracking space is LOCAL: its origin at the eyes of a person standing at the scene (Wedge's
// scenes map it to the world by their interaction origin, (0, 1.6, 0) in the shipped ones), y up. STAGE
// has its origin on the floor kStageDepth below it, as a real runtime's floor-level stage would.
inline constexpr double kStageDepth = 1.6;  // m

// The head of a recording without head samples: half a metre behind the tracking origin (the scene's
// interaction point), at its height, looking 35 degrees down at it: a person at a table.
inline Pose default_head() {
  Pose p;
  p.position = Eigen::Vector3d(0.0, 0.0, 0.5);
  p.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(-35.0 * M_PI / 180.0, Eigen::Vector3d::UnitX()));
  return p;
}

inline constexpr int kLeft = 0, kRight = 1, kHandCount = 2;

// What an input component of a Touch controller reads, per sample. Booleans are 0 or 1. The *AsBool
// channels are the analog ones read as a button, with hysteresis: on at >= 0.55, off again at <= 0.45,
// stepped through the samples in order (so the answer depends on the recording, not on when the app syncs).
enum class Channel : uint8_t {
  Squeeze,         // squeeze/value
  Trigger,         // trigger/value
  TriggerTouch,    // trigger/touch: the trigger is touched when it reads above 0
  SqueezeAsBool,   // squeeze/value through the threshold
  TriggerAsBool,   // trigger/value through the threshold (also simple_controller's select/click)
  PrimaryClick,    // a/click (right), x/click (left): the A / X bit, or the recording's mode4d flag
  PrimaryTouch,    // a/touch, x/touch: as the click (a pressed button is touched)
  SecondaryClick,  // b/click (right), y/click (left)
  SecondaryTouch,  // b/touch, y/touch
  Zero,            // inputs the recordings do not have (thumbstick, thumbrest, menu, system): always 0
  Count
};

struct ChannelValue {
  double value = 0.0;
  XrTime changed_at = kEpoch;  // XrTime of the sample at which the value became what it is (kEpoch: never changed)
};

struct TrackedPose {
  bool tracked = false;  // false before the hand's first sample (and always without a recording)
  Pose pose;             // tracking space (STAGE = LOCAL)
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();   // m/s, of the blended segment (0 when held)
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // rad/s, tracking space
};

class Playback {
 public:
  Playback() = default;  // no recording: hands untracked, head at default_head(), never ends
  // lose_tracking: a hand is untracked across gaps of more than 0.1 s (WEDGE_XR_QUIRKS=lose-tracking).
  explicit Playback(const recordings::Recording& r, bool lose_tracking = false);

  TrackedPose grip(int hand, XrTime t) const;  // the recorded hand pose is the grip pose
  TrackedPose head(XrTime t) const;            // always tracked
  ChannelValue channel(int hand, Channel c, XrTime t) const;
  // The last sample's XrTime over every stream; empty without a recording (the session never stops by itself).
  std::optional<XrTime> end_time() const { return end_; }

 private:
  struct Track {  // one stream of poses
    std::vector<XrTime> times;
    std::vector<Pose> poses;
  };
  struct HandStream {
    Track track;
    std::array<std::vector<double>, std::size_t(Channel::Count)> values;   // per channel, per sample
    std::array<std::vector<XrTime>, std::size_t(Channel::Count)> changed;  // per channel, per sample
  };
  static TrackedPose sample(const Track& track, XrTime t, bool hold_first);

  std::array<HandStream, kHandCount> hands_;
  Track head_;
  std::optional<XrTime> end_;
  bool lose_tracking_ = false;
};

}  // namespace wedge::xr_replay

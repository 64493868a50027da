// Recorded device streams as the input layer's frames at the simulation's fixed step, so that a replay is a pure
// function of (scene, recordings). The rule, for the frame at time t (docs/input.md):
//   - a hand's pose is interpolated between its last sample at or before t and the next one (position
//     linearly, orientation by slerp) when they are at most max_gap apart, else held from the last one;
//     before its first sample the hand is not tracked;
//   - squeeze, trigger, buttons and the 4D-mode flag are the last sample's (a button is pressed or not);
//     4D mode is the recording's flag, or A held on the right controller, X on the left;
//   - accelerometer samples with time in (previous frame's t, t] are handed over in order, each at its
//     own time (the gravity filter runs at the device's rate).
// Several recordings (controllers, a phone) merge by time; each stream (left hand, right hand,
// accelerometer) may come from one of them only.
#pragma once

#include <string>
#include <vector>

#include "wedge/input/frame.hpp"
#include "wedge/recordings/recording.hpp"

namespace wedge::recordings {

class RecordingSource {
 public:
  static constexpr double kMaxGap = 0.1;  // s: longer gaps (tracking lost) hold the last pose

  // `names` label the recordings in messages (their files). Throws wedge::Error if two recordings carry
  // the same stream.
  RecordingSource(std::vector<Recording> recordings, const std::vector<std::string>& names);

  // The frame at time t; t must not decrease from one call to the next (throws wedge::Error).
  const input::InputFrame& frame_at(double t);

  double duration() const { return duration_; }  // s, the last sample of any stream
  bool has_hands() const { return !hands_[0].empty() || !hands_[1].empty(); }
  bool has_motion() const { return !motion_.empty(); }
  bool uses_mode4d() const { return uses_mode4d_; }
  bool uses_tilt() const { return uses_tilt_; }
  // Where each stream came from (index into the constructor's names, -1 if none).
  int source_of_hand(int hand) const { return hand_source_[hand]; }
  int source_of_motion() const { return motion_source_; }

 private:
  std::array<std::vector<HandSample>, input::kHandCount> hands_;
  std::vector<MotionSample> motion_;
  std::array<std::size_t, input::kHandCount> cursor_{};  // first sample with time > t (so cursor - 1 is at or before)
  std::size_t motion_cursor_ = 0;
  std::array<int, input::kHandCount> hand_source_{-1, -1};
  int motion_source_ = -1;
  double duration_ = 0.0, last_t_ = -1.0;
  bool uses_mode4d_ = false, uses_tilt_ = false;
  input::InputFrame frame_;
};

}  // namespace wedge::recordings

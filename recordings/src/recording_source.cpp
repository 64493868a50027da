// Resampling recorded streams to step times (recording_source.hpp has the rule).
#include "wedge/recordings/recording_source.hpp"

#include <algorithm>

#include "wedge/error.hpp"

namespace wedge::recordings {

namespace {
bool in_4d_mode(const HandSample& s) {
  const std::uint32_t own = s.hand == Hand::Right ? kButtonA : kButtonX;
  return s.mode4d || (s.buttons & own) != 0;
}
}  // namespace

RecordingSource::RecordingSource(std::vector<Recording> recs, const std::vector<std::string>& names) {
  auto label = [&](std::size_t i) { return i < names.size() ? names[i] : "recording " + std::to_string(i + 1); };
  for (std::size_t r = 0; r < recs.size(); ++r) {
    Recording& rec = recs[r];
    duration_ = std::max(duration_, rec.duration());
    for (int k = 0; k < input::kHandCount; ++k) {
      const bool has = std::any_of(rec.hands.begin(), rec.hands.end(), [k](const auto& s) { return int(s.hand) == k; });
      if (!has) continue;
      if (hand_source_[k] >= 0)
        throw Error(label(r) + ": the " + (k == 0 ? "left" : "right") + " hand is also in " +
                    label(std::size_t(hand_source_[k])) + " (each stream may come from one recording)");
      hand_source_[k] = int(r);
    }
    if (!rec.motion.empty()) {
      if (motion_source_ >= 0)
        throw Error(label(r) + ": accelerometer samples are also in " + label(std::size_t(motion_source_)) +
                    " (each stream may come from one recording)");
      motion_source_ = int(r);
      motion_ = std::move(rec.motion);
    }
    for (const HandSample& s : rec.hands) {
      hands_[int(s.hand)].push_back(s);
      uses_mode4d_ = uses_mode4d_ || in_4d_mode(s);
    }
  }
  for (const MotionSample& m : motion_) uses_tilt_ = uses_tilt_ || m.tilt;
}

const input::InputFrame& RecordingSource::frame_at(double t) {
  if (!(t >= last_t_)) throw Error("RecordingSource: frames must be asked for in time order");
  frame_.t = t;
  for (int k = 0; k < input::kHandCount; ++k) {
    const std::vector<HandSample>& s = hands_[k];
    std::size_t& c = cursor_[k];
    while (c < s.size() && s[c].t <= t) ++c;
    input::HandInput& in = frame_.hands[k];
    if (c == 0) {
      in = input::HandInput{};
      continue;
    }
    const HandSample& a = s[c - 1];
    in.tracked = true;
    in.position = a.pose.position;
    in.orientation = a.pose.orientation;
    in.squeeze = a.squeeze;
    in.trigger = a.trigger;
    in.buttons = a.buttons;
    in.mode4d = in_4d_mode(a);
    if (c < s.size() && s[c].t - a.t <= kMaxGap && s[c].t > a.t) {
      const HandSample& b = s[c];
      const double u = (t - a.t) / (b.t - a.t);
      in.position = a.pose.position + u * (b.pose.position - a.pose.position);
      in.orientation = a.pose.orientation.slerp(u, b.pose.orientation);
    }
  }
  const std::size_t first = motion_cursor_;
  while (motion_cursor_ < motion_.size() && motion_[motion_cursor_].t <= t) ++motion_cursor_;
  frame_.motion = std::span<const MotionSample>(motion_.data() + first, motion_cursor_ - first);
  last_t_ = t;
  return frame_;
}

}  // namespace wedge::recordings

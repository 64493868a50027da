// Sampling the recording at an XrTime (playback.hpp has the rule).
#include "playback.hpp"

#include <algorithm>

#include "wedge/recordings/recording.hpp"

namespace wedge::xr_replay {

namespace {

using recordings::HandSample;

// The button a hand's primary / secondary channel reads (A, B on the right controller; X, Y on the left).
bool primary_down(const HandSample& s) {
  const std::uint32_t bit = s.hand == recordings::Hand::Right ? recordings::kButtonA : recordings::kButtonX;
  return s.mode4d || (s.buttons & bit) != 0;
}
bool secondary_down(const HandSample& s) {
  const std::uint32_t bit = s.hand == recordings::Hand::Right ? recordings::kButtonB : recordings::kButtonY;
  return (s.buttons & bit) != 0;
}

// The analog value read as a button: on at >= 0.55, off at <= 0.45, else as before.
bool threshold(bool was_on, double v) { return was_on ? v > 0.45 : v >= 0.55; }

}  // namespace

Playback::Playback(const recordings::Recording& r, bool lose_tracking) : lose_tracking_(lose_tracking) {
  end_ = recording_to_xr_time(r.duration());  // 0 s for an empty recording: it ends at once
  std::array<bool, kHandCount> squeeze_on{}, trigger_on{};
  for (const HandSample& s : r.hands) {
    HandStream& h = hands_[int(s.hand)];
    const XrTime t = recording_to_xr_time(s.t);
    h.track.times.push_back(t);
    h.track.poses.push_back({s.pose.position, s.pose.orientation});
    const int k = int(s.hand);
    squeeze_on[k] = threshold(squeeze_on[k], s.squeeze);
    trigger_on[k] = threshold(trigger_on[k], s.trigger);
    const std::array<double, std::size_t(Channel::Count)> v = {
        s.squeeze, s.trigger, s.trigger > 0.0 ? 1.0 : 0.0, squeeze_on[k] ? 1.0 : 0.0, trigger_on[k] ? 1.0 : 0.0,
        primary_down(s) ? 1.0 : 0.0, primary_down(s) ? 1.0 : 0.0, secondary_down(s) ? 1.0 : 0.0,
        secondary_down(s) ? 1.0 : 0.0, 0.0};
    for (std::size_t c = 0; c < v.size(); ++c) {
      // Before the first sample every input rests at 0 (changed at kEpoch); a sample that reads otherwise
      // is where it changed.
      const double before = h.values[c].empty() ? 0.0 : h.values[c].back();
      const XrTime since = h.changed[c].empty() ? kEpoch : h.changed[c].back();
      h.values[c].push_back(v[c]);
      h.changed[c].push_back(v[c] != before ? t : since);
    }
  }
  for (const recordings::HeadSample& s : r.heads) {
    head_.times.push_back(recording_to_xr_time(s.t));
    head_.poses.push_back({s.pose.position, s.pose.orientation});
  }
}

TrackedPose Playback::sample(const Track& track, XrTime t, bool hold_first) {
  TrackedPose out;
  const auto& ts = track.times;
  // c = number of samples at or before t.
  const std::size_t c = std::size_t(std::upper_bound(ts.begin(), ts.end(), t) - ts.begin());
  if (c == 0) {
    if (!hold_first || ts.empty()) return out;
    out.tracked = true;
    out.pose = track.poses.front();
    return out;
  }
  const Pose& a = track.poses[c - 1];
  out.tracked = true;
  out.pose = a;
  if (c < ts.size() && ts[c] > ts[c - 1] && ts[c] - ts[c - 1] <= kInterpolationGap) {
    const Pose& b = track.poses[c];
    const double dt = double(ts[c] - ts[c - 1]);
    const double u = double(t - ts[c - 1]) / dt;
    out.pose.position = a.position + u * (b.position - a.position);
    out.pose.orientation = a.orientation.slerp(u, b.orientation);
    // The segment's constant velocities: (b - a) / dt, and the turn a -> b (Eigen's angle-axis takes the
    // short way round, as slerp does) over dt.
    out.linear_velocity = (b.position - a.position) / (dt * 1e-9);
    const Eigen::AngleAxisd turn(b.orientation * a.orientation.conjugate());
    out.angular_velocity = turn.axis() * (turn.angle() / (dt * 1e-9));
  }
  return out;
}

TrackedPose Playback::grip(int hand, XrTime t) const {
  const Track& track = hands_[hand].track;
  if (lose_tracking_) {  // inside a gap of more than 0.1 s: lost (after the last sample: held, as always)
    const std::size_t c = std::size_t(std::upper_bound(track.times.begin(), track.times.end(), t) - track.times.begin());
    if (c > 0 && c < track.times.size() && t > track.times[c - 1] && track.times[c] - track.times[c - 1] > kInterpolationGap)
      return {};
  }
  return sample(track, t, false);
}

TrackedPose Playback::head(XrTime t) const {
  if (head_.times.empty()) {
    TrackedPose out;
    out.tracked = true;
    out.pose = default_head();
    return out;
  }
  return sample(head_, t, true);
}

ChannelValue Playback::channel(int hand, Channel c, XrTime t) const {
  const HandStream& h = hands_[hand];
  const auto& ts = h.track.times;
  const std::size_t n = std::size_t(std::upper_bound(ts.begin(), ts.end(), t) - ts.begin());
  if (n == 0) return {};
  return {h.values[std::size_t(c)][n - 1], h.changed[std::size_t(c)][n - 1]};
}

}  // namespace wedge::xr_replay

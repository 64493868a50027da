// The session's clock against the runtime's display times. Time t = 0 (s) is the first frame's display
// time X0 (XrTime, integer ns); step k of h seconds is at X0 + round(k h 1e9) ns, and a frame runs the
// steps whose times are at or before its display time, each with the controllers located at that step's
// own time (so the physics sees input at its fixed rate whatever the display rate).
//
// A frame's display time is the runtime's predicted one when it is valid: > 0 and later than the last.
// Runtimes deviate: Monado's headless mode predicts 0 and never blocks in xrWaitFrame. Then the frame
// takes the runtime's clock now (XR_KHR_convert_timespec_time; the machine's monotonic clock without it),
// and the app paces itself by sleeping to the display period. A time <= 0 is never passed on.
#pragma once

#include <openxr/openxr.h>

#include <chrono>
#include <cmath>
#include <cstdint>

namespace wedge::xr {

inline constexpr XrDuration kDefaultDisplayPeriod = 11'111'111;  // ns: 90 Hz, when the runtime gives none

class FrameClock {
 public:
  // This frame's display time (see above); `runtime_now` is the runtime's clock (0 if it has none).
  XrTime frame_time(const XrFrameState& state, XrTime runtime_now);

  bool started() const { return started_; }
  bool paced() const { return paced_; }  // the app has paced itself at least once
  XrTime origin() const { return origin_; }
  // Step k's time: X0 + round(k h 1e9).
  XrTime step_time(std::int64_t k, double h) const { return origin_ + XrTime(std::llround(double(k) * h * 1e9)); }
  // The session time (s) of an XrTime.
  double seconds(XrTime t) const { return double(t - origin_) * 1e-9; }

 private:
  bool started_ = false, paced_ = false;
  XrTime origin_ = 0, last_ = 0;
  std::chrono::steady_clock::time_point last_wall_{};
};

}  // namespace wedge::xr

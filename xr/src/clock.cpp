#include "wedge/xr/clock.hpp"

#include <thread>

namespace wedge::xr {

XrTime FrameClock::frame_time(const XrFrameState& state, XrTime runtime_now) {
  XrTime t = state.predictedDisplayTime;
  if (!(t > 0 && (!started_ || t > last_))) {
    // The runtime's prediction cannot be used: sleep to the display period, then take a clock.
    const XrDuration period = state.predictedDisplayPeriod > 0 ? state.predictedDisplayPeriod : kDefaultDisplayPeriod;
    if (started_) std::this_thread::sleep_until(last_wall_ + std::chrono::nanoseconds(period));
    paced_ = true;
    t = runtime_now > 0 ? runtime_now
                        : XrTime(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                     std::chrono::steady_clock::now().time_since_epoch())
                                     .count());
    if (started_ && t <= last_) t = last_ + period;  // (never backwards, never twice the same)
    if (t <= 0) t = period;
  }
  last_wall_ = std::chrono::steady_clock::now();
  if (!started_) {
    started_ = true;
    origin_ = t;
  }
  last_ = t;
  return t;
}

}  // namespace wedge::xr

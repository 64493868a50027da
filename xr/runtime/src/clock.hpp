// The runtime's two clocks (docs/xr-runtime.md, "Clock").
//
// The frame clock is deterministic and never reads the wall clock: frame n of a session (n = 0, 1, ...,
// counted by xrWaitFrame) is displayed at kEpoch + round(n * 1e9 / 90) ns, and XrTime kEpoch is time 0 of
// the recording, so a sample at t seconds is at XrTime kEpoch + llround(t * 1e9). Every comparison against
// the recording is made in these integer nanoseconds.
//
// XR_KHR_convert_timespec_time is the wall clock's: CLOCK_MONOTONIC maps linearly onto XrTime, with "now" at
// xrCreateInstance mapped to kEpoch. The two clocks start together and drift apart (the frame clock runs as
// fast as the app calls xrWaitFrame); apps that pace themselves on the frame clock stay deterministic.
#pragma once

#include <cstdint>

#include "xr_platform.hpp"

namespace wedge::xr_replay {

inline constexpr XrTime kEpoch = 1'000'000'000;              // XrTime of recording time 0 (1 s: positive)
inline constexpr XrDuration kFramePeriod = 11'111'111;       // round(1e9 / 90) ns, the 90 Hz display period
inline constexpr XrDuration kInterpolationGap = 100'000'000;  // samples further apart than this are not blended

// kEpoch + round(n * 1e9 / 90), exactly: n * 1e9 / 90 = n * 1e8 / 9, whose fraction is never one half.
constexpr XrTime frame_display_time(uint64_t n) {
  return kEpoch + XrTime((n * 200'000'000ull + 9) / 18);
}

// A recording's sample time (seconds) as XrTime, and back.
XrTime recording_to_xr_time(double t_seconds);
double xr_time_to_recording_seconds(XrTime t);

// The fixed linear map between CLOCK_MONOTONIC and XrTime, set when the instance is created.
struct TimespecMap {
  int64_t monotonic_at_epoch_ns = 0;  // CLOCK_MONOTONIC (ns) at xrCreateInstance
  static TimespecMap now();
  XrTime to_xr(const timespec& ts) const;
  timespec to_timespec(XrTime t) const;
};

}  // namespace wedge::xr_replay

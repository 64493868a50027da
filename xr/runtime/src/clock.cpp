// Recording time <-> XrTime and the CLOCK_MONOTONIC map (clock.hpp has the rules).
#include "clock.hpp"

#include <cmath>

namespace wedge::xr_replay {

static_assert(frame_display_time(0) == kEpoch && frame_display_time(1) == kEpoch + 11'111'111 &&
              frame_display_time(2) == kEpoch + 22'222'222 && frame_display_time(5) == kEpoch + 55'555'556 &&
              frame_display_time(90) == kEpoch + 1'000'000'000);

XrTime recording_to_xr_time(double t_seconds) { return kEpoch + std::llround(t_seconds * 1e9); }

double xr_time_to_recording_seconds(XrTime t) { return double(t - kEpoch) / 1e9; }

TimespecMap TimespecMap::now() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return {int64_t(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec};
}

XrTime TimespecMap::to_xr(const timespec& ts) const {
  return kEpoch + (int64_t(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec - monotonic_at_epoch_ns);
}

timespec TimespecMap::to_timespec(XrTime t) const {
  const int64_t ns = t - kEpoch + monotonic_at_epoch_ns;
  timespec ts{};
  ts.tv_sec = ns / 1'000'000'000;
  ts.tv_nsec = ns % 1'000'000'000;
  if (ts.tv_nsec < 0) {
    ts.tv_nsec += 1'000'000'000;
    ts.tv_sec -= 1;
  }
  return ts;
}

}  // namespace wedge::xr_replay

// The haptics log (WEDGE_XR_HAPTICS_LOG): every xrApplyHapticFeedback / xrStopHapticFeedback that reaches a
// hand's /output/haptic is appended as one JSON Lines record and flushed, so a test (or a crashed app's
// post-mortem) reads every call made so far:
//   {"call":"apply","time_ns":T,"t":S,"hand":"/user/hand/right","amplitude":A,"duration_ns":D,"frequency":F}
//   {"call":"stop","time_ns":T,"t":S,"hand":"/user/hand/right"}
// time_ns is the session's frame time (the latest predicted display time), t the same on the recording's
// clock in seconds; duration_ns is as the app gave it (-1 is XR_MIN_HAPTIC_DURATION), frequency 0 is
// XR_FREQUENCY_UNSPECIFIED.
#pragma once

#include <cstdio>
#include <memory>
#include <string>
#include <string_view>

#include "xr_platform.hpp"

namespace wedge::xr_replay {

class HapticsLog {
 public:
  void set_path(std::string path) { path_ = std::move(path); }
  void apply(XrTime now, std::string_view hand, const XrHapticVibration& v);
  void stop(XrTime now, std::string_view hand);

 private:
  void write(const std::string& line);
  struct Close {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  std::string path_;                     // "" = no log
  std::unique_ptr<std::FILE, Close> file_;  // opened (appending) at the first call
};

}  // namespace wedge::xr_replay

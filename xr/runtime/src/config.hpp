// The runtime's settings, all from environment variables read once at xrCreateInstance (docs/xr-runtime.md
// lists them). A malformed value fails xrCreateInstance: a test that sets one wants it obeyed, not ignored.
#pragma once

#include <cstdint>
#include <string>

namespace wedge::xr_replay {

struct Config {
  std::string replay_path;      // WEDGE_XR_REPLAY: the recording to play ("" = none: hands never tracked)
  uint32_t eye_width = 640;     // WEDGE_XR_EYE_SIZE=WxH: recommended swapchain size of each eye
  uint32_t eye_height = 720;
  std::string haptics_log;      // WEDGE_XR_HAPTICS_LOG: JSON Lines file the haptic calls are appended to
  std::string frames_dir;       // WEDGE_XR_FRAMES: folder the submitted eye images go to as PNG
  uint32_t frames_every = 1;    // WEDGE_XR_FRAMES_EVERY=K: write every K-th submitted frame
  bool refuse_system = false;   // WEDGE_XR_REFUSE=system: xrGetSystem fails (XR_ERROR_FORM_FACTOR_UNAVAILABLE)
  bool refuse_session = false;  // WEDGE_XR_REFUSE=session: xrCreateSession fails (XR_ERROR_RUNTIME_FAILURE)
  // WEDGE_XR_QUIRKS, a comma-separated list of ways real runtimes deviate, so that an app's survival of
  // them can be tested:
  //   zero-display-time: xrWaitFrame predicts a display time of 0, as Monado's headless mode does (the
  //     runtime's own frame clock goes on underneath);
  //   lose-tracking: a hand is not tracked across a gap of more than 0.1 s between its samples (the
  //     recordings' own rule holds the pose there), as a controller that leaves the cameras' view;
  //   refuse-binding=PATH: xrSuggestInteractionProfileBindings refuses any suggestion holding the binding
  //     PATH (XR_ERROR_PATH_UNSUPPORTED), as a runtime that does not know one component.
  bool zero_display_time = false;
  bool lose_tracking = false;
  std::string refused_binding;
};

// Fills `out` from the environment. Returns "" on success, else one line naming the variable and the problem.
std::string read_config(Config& out);

// Prints one line to stderr, prefixed "Wedge replay runtime: ".
void report(const std::string& line);

}  // namespace wedge::xr_replay

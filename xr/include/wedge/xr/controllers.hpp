// Two hand controllers through OpenXR's action system, by the conventions (as hello_xr does it): one
// action set "wedge" whose actions take the subaction paths /user/hand/left and /user/hand/right: grip
// and aim poses, grab (the squeeze), trigger, 4D mode, the slice along w, reset, and a haptic output.
// Bindings are suggested for khr/simple_controller, oculus/touch_controller, valve/index_controller,
// htc/vive_controller and microsoft/motion_controller (docs/xr.md has the table); a binding the runtime
// refuses is dropped and logged, and the rest of its profile kept.
//
// Input for one physics step at time t, which lies between the last frame's xrSyncActions and this
// one's: the grip pose located at t itself; the grab, trigger and 4D button as they were at t: the state
// synced this frame if it last changed at or before t, else the one before it (OpenXR's lastChangeTime).
// A hand whose pose is not valid (position and orientation both) holds its last pose for up to kMaxGap
// (the recordings' rule), and then lets go: it stays where it was with nothing pressed until it is
// tracked again.
#pragma once

#include <openxr/openxr.h>

#include <array>
#include <map>
#include <optional>
#include <string>

#include "wedge/input/frame.hpp"
#include "wedge/xr/instance.hpp"
#include "wedge/xr/session.hpp"

namespace wedge::xr {

class Controllers {
 public:
  static constexpr XrDuration kMaxGap = 100'000'000;  // ns (0.1 s): a lost hand's pose is held this long

  // Creates the actions, suggests the bindings, attaches the set to the session. Throws XrError.
  Controllers(const Instance& instance, const Session& session, Log log);
  ~Controllers();
  Controllers(const Controllers&) = delete;
  Controllers& operator=(const Controllers&) = delete;

  // Once per frame after xrWaitFrame: xrSyncActions when the session is focused, and the states. Not
  // focused, every action is inactive and the hands count as lost.
  void sync();

  // A hand's input at time t (see above). Times must not decrease from one call to the next per hand.
  input::HandInput hand_at(int hand, XrTime t);
  // The head's pose at t (the VIEW space), if the runtime knows it.
  std::optional<input::Pose> head_at(XrTime t) const;
  // The aim pose at t, for drawing the controller's ray.
  std::optional<input::Pose> aim_at(int hand, XrTime t) const;

  double slice_rate() const;    // [-1, 1]: the thumbstick's or trackpad's y, the larger of the two hands
  bool reset_pressed() const;   // the reset button went down at the last sync
  // One haptic pulse on a hand (amplitude [0, 1], duration s, frequency Hz, 0 = the runtime's default).
  void pulse(int hand, double amplitude, double duration, double frequency);
  // Logs each hand's current interaction profile (after an INTERACTION_PROFILE_CHANGED event).
  void log_profiles() const;

 private:
  // A synced value and the one before it, with the time it changed between them.
  struct Sampled {
    double now = 0.0, before = 0.0;
    XrTime changed = 0;
    double at(XrTime t) const { return t < changed ? before : now; }
  };
  struct Hand {
    XrPath path = XR_NULL_PATH;
    XrSpace grip = XR_NULL_HANDLE, aim = XR_NULL_HANDLE;
    bool pose_active = false;
    Sampled grab, trigger, mode4d;
    double slice = 0.0;
    bool reset = false, reset_was = false;
    // Tracking: the last valid pose and its time.
    bool ever = false;
    input::Pose last;
    XrTime last_valid = 0;
  };

  XrAction make_action(const char* name, const char* localized, XrActionType type);
  void suggest_bindings();
  void read_states();
  std::optional<input::Pose> locate(XrSpace space, XrTime t) const;

  const Instance& instance_;
  const Session& session_;
  Log log_;
  XrActionSet set_ = XR_NULL_HANDLE;
  XrAction grip_ = XR_NULL_HANDLE, aim_ = XR_NULL_HANDLE, grab_ = XR_NULL_HANDLE, trigger_ = XR_NULL_HANDLE,
           mode4d_ = XR_NULL_HANDLE, slice_ = XR_NULL_HANDLE, reset_ = XR_NULL_HANDLE, haptic_ = XR_NULL_HANDLE;
  std::map<std::string, XrAction> by_name_;
  std::array<Hand, input::kHandCount> hands_;
  bool focused_ = false;
  std::map<XrResult, bool> haptic_failures_;  // logged once per result
};

}  // namespace wedge::xr

// The OpenXR session and its life: created on the instance's system (with an OpenGL binding to render,
// or none when headless), begun when the runtime says READY, ended when it says STOPPING, and over on
// EXITING, LOSS_PENDING, instance loss or an exit request (hello_xr's state handling, written for Wedge).
// Every state change is logged as one line.
//
// The tracking space is the recordings' and the scenes': its origin at the eyes of a person standing at
// the scene, y up (a scene's interaction origin, (0, 1.6, 0) in the shipped ones, is where that point is
// in the world). Where the runtime has a STAGE (origin on the real floor) it is the STAGE raised by a
// standing eye height, so that the scene's floor lies on the room's; else it is LOCAL (origin at the eyes
// when the session began), and the floor is where the scene's interaction origin puts it.
#pragma once

#include <openxr/openxr.h>

#include <functional>
#include <string>
#include <vector>

#include "wedge/xr/instance.hpp"

namespace wedge::xr {

using Log = std::function<void(const std::string&)>;

inline constexpr double kStandingEyeHeight = 1.6;  // m: the tracking origin above a STAGE's floor

class Session {
 public:
  // `graphics_binding`: an XrGraphicsBinding* struct for xrCreateSession's next chain, or null for a
  // headless session (the instance must then be headless). Throws XrError.
  Session(const Instance& instance, const void* graphics_binding, Log log);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // Drains the runtime's events and acts on them: READY -> xrBeginSession, STOPPING -> xrEndSession,
  // EXITING / LOSS_PENDING / instance loss -> done(). Returns true when the interaction profile changed.
  bool poll_events();
  // Asks the runtime to stop the session (xrRequestExitSession) if it runs; done() follows in due course.
  void request_exit();

  XrSessionState state() const { return state_; }
  bool running() const { return running_; }  // between xrBeginSession and xrEndSession
  bool focused() const { return state_ == XR_SESSION_STATE_FOCUSED; }
  bool visible() const { return state_ == XR_SESSION_STATE_VISIBLE || state_ == XR_SESSION_STATE_FOCUSED; }
  bool done() const { return done_; }
  const std::string& end_reason() const { return end_reason_; }

  XrSession handle() const { return session_; }
  XrSpace space() const { return space_; }       // tracking space (STAGE raised to eye height, or LOCAL)
  XrSpace view_space() const { return view_; }   // the head
  bool stage() const { return stage_; }
  static constexpr XrViewConfigurationType kViewConfiguration = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;

  // The frame calls. wait_frame may return a predictedDisplayTime of 0 (Monado headless does): clock.hpp
  // decides what time the frame has. begin_frame returns false when the runtime refuses (logged once);
  // the caller then submits nothing.
  XrFrameState wait_frame();
  bool begin_frame();
  void end_frame(XrTime display_time, const std::vector<const XrCompositionLayerBaseHeader*>& layers);

 private:
  void on_state(XrSessionState state, XrTime time);

  const Instance& instance_;
  Log log_;
  XrSession session_ = XR_NULL_HANDLE;
  XrSpace space_ = XR_NULL_HANDLE, view_ = XR_NULL_HANDLE;
  XrSessionState state_ = XR_SESSION_STATE_UNKNOWN;
  bool stage_ = false, running_ = false, done_ = false, exit_requested_ = false, refused_logged_ = false;
  std::string end_reason_;
};

// The state's name without its prefix ("FOCUSED").
std::string state_name(XrSessionState state);

}  // namespace wedge::xr

#include "wedge/xr/session.hpp"

#include <openxr/openxr_reflection.h>

#include <algorithm>

#include "wedge/xr/check.hpp"

namespace wedge::xr {

std::string state_name(XrSessionState state) {
  switch (state) {
#define WEDGE_XR_STATE_CASE(name, value) \
  case name:                             \
    return std::string(#name).substr(std::string("XR_SESSION_STATE_").size());
    XR_LIST_ENUM_XrSessionState(WEDGE_XR_STATE_CASE)
#undef WEDGE_XR_STATE_CASE
    default:
      return "XrSessionState(" + std::to_string(int(state)) + ")";
  }
}

Session::Session(const Instance& instance, const void* graphics_binding, Log log)
    : instance_(instance), log_(std::move(log)) {
  XrSessionCreateInfo info{XR_TYPE_SESSION_CREATE_INFO};
  info.next = graphics_binding;
  info.systemId = instance.system();
  check(instance.handle(), xrCreateSession(instance.handle(), &info, &session_), "xrCreateSession");
  try {
    std::uint32_t count = 0;
    check(instance.handle(), xrEnumerateReferenceSpaces(session_, 0, &count, nullptr), "xrEnumerateReferenceSpaces");
    std::vector<XrReferenceSpaceType> spaces(count);
    check(instance.handle(), xrEnumerateReferenceSpaces(session_, count, &count, spaces.data()),
          "xrEnumerateReferenceSpaces");
    stage_ = std::find(spaces.begin(), spaces.end(), XR_REFERENCE_SPACE_TYPE_STAGE) != spaces.end();
    XrReferenceSpaceCreateInfo space{XR_TYPE_REFERENCE_SPACE_CREATE_INFO};
    space.poseInReferenceSpace.orientation.w = 1.0f;
    space.referenceSpaceType = stage_ ? XR_REFERENCE_SPACE_TYPE_STAGE : XR_REFERENCE_SPACE_TYPE_LOCAL;
    if (stage_) space.poseInReferenceSpace.position.y = float(kStandingEyeHeight);
    check(instance.handle(), xrCreateReferenceSpace(session_, &space, &space_), "xrCreateReferenceSpace");
    XrReferenceSpaceCreateInfo view{XR_TYPE_REFERENCE_SPACE_CREATE_INFO};
    view.poseInReferenceSpace.orientation.w = 1.0f;
    view.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_VIEW;
    check(instance.handle(), xrCreateReferenceSpace(session_, &view, &view_), "xrCreateReferenceSpace(VIEW)");
    if (!stage_) log_("the runtime has no STAGE space: tracking in LOCAL (the floor is where the scene's interaction origin puts it)");
  } catch (...) {
    xrDestroySession(session_);
    throw;
  }
}

Session::~Session() {
  if (view_ != XR_NULL_HANDLE) xrDestroySpace(view_);
  if (space_ != XR_NULL_HANDLE) xrDestroySpace(space_);
  if (session_ != XR_NULL_HANDLE) xrDestroySession(session_);
}

bool Session::poll_events() {
  bool profile_changed = false;
  for (;;) {
    XrEventDataBuffer event{XR_TYPE_EVENT_DATA_BUFFER};
    const XrResult r = check(instance_.handle(), xrPollEvent(instance_.handle(), &event), "xrPollEvent");
    if (r == XR_EVENT_UNAVAILABLE) break;
    switch (event.type) {
      case XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED: {
        const auto& e = reinterpret_cast<const XrEventDataSessionStateChanged&>(event);
        if (e.session == session_) on_state(e.state, e.time);
        break;
      }
      case XR_TYPE_EVENT_DATA_INTERACTION_PROFILE_CHANGED:
        profile_changed = true;
        break;
      case XR_TYPE_EVENT_DATA_INSTANCE_LOSS_PENDING:
        log_("the runtime is going away (instance loss pending): ending");
        done_ = true;
        end_reason_ = "instance loss";
        break;
      case XR_TYPE_EVENT_DATA_EVENTS_LOST: {
        const auto& e = reinterpret_cast<const XrEventDataEventsLost&>(event);
        log_("the runtime lost " + std::to_string(e.lostEventCount) + " events");
        break;
      }
      default:
        break;
    }
  }
  return profile_changed;
}

void Session::on_state(XrSessionState state, XrTime time) {
  log_("session " + state_name(state) + " (at " + std::to_string(time) + " ns)");
  state_ = state;
  switch (state) {
    case XR_SESSION_STATE_READY: {
      XrSessionBeginInfo begin{XR_TYPE_SESSION_BEGIN_INFO};
      begin.primaryViewConfigurationType = kViewConfiguration;
      check(instance_.handle(), xrBeginSession(session_, &begin), "xrBeginSession");
      running_ = true;
      break;
    }
    case XR_SESSION_STATE_STOPPING:
      check(instance_.handle(), xrEndSession(session_), "xrEndSession");
      running_ = false;
      if (exit_requested_) {  // (the runtime's EXITING follows; nothing more to wait for)
        done_ = true;
        end_reason_ = "exit requested";
      }
      break;
    case XR_SESSION_STATE_EXITING:
      done_ = true;
      if (end_reason_.empty()) end_reason_ = exit_requested_ ? "exit requested" : "the runtime ended the session";
      break;
    case XR_SESSION_STATE_LOSS_PENDING:
      done_ = true;
      end_reason_ = "session lost (LOSS_PENDING)";
      break;
    default:
      break;
  }
}

void Session::request_exit() {
  if (exit_requested_) return;
  exit_requested_ = true;
  if (!running_) {
    done_ = true;
    end_reason_ = "exit requested";
    return;
  }
  check(instance_.handle(), xrRequestExitSession(session_), "xrRequestExitSession");
}

XrFrameState Session::wait_frame() {
  XrFrameWaitInfo info{XR_TYPE_FRAME_WAIT_INFO};
  XrFrameState state{XR_TYPE_FRAME_STATE};
  check(instance_.handle(), xrWaitFrame(session_, &info, &state), "xrWaitFrame");
  return state;
}

bool Session::begin_frame() {
  XrFrameBeginInfo info{XR_TYPE_FRAME_BEGIN_INFO};
  const XrResult r = xrBeginFrame(session_, &info);
  if (XR_FAILED(r)) {
    if (!refused_logged_) log_("xrBeginFrame refused (" + result_name(instance_.handle(), r) + "): submitting no frames");
    refused_logged_ = true;
    return false;
  }
  return true;  // (XR_FRAME_DISCARDED: the previous frame was dropped; this one goes on)
}

void Session::end_frame(XrTime display_time, const std::vector<const XrCompositionLayerBaseHeader*>& layers) {
  XrFrameEndInfo info{XR_TYPE_FRAME_END_INFO};
  info.displayTime = display_time;
  info.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
  info.layerCount = std::uint32_t(layers.size());
  info.layers = layers.data();
  check(instance_.handle(), xrEndFrame(session_, &info), "xrEndFrame");
}

}  // namespace wedge::xr

// Sessions and their state machine (session_state.hpp has the transitions).
#include "api.hpp"
#include "registry.hpp"
#include "session_state.hpp"
#include "system.hpp"
#include "validate.hpp"

namespace wedge::xr_replay {

namespace {

// Graphics bindings of APIs the runtime does not offer: a session with one of them cannot be made.
bool is_other_graphics_binding(XrStructureType t) {
  switch (t) {
    case XR_TYPE_GRAPHICS_BINDING_OPENGL_XCB_KHR:
    case XR_TYPE_GRAPHICS_BINDING_OPENGL_WAYLAND_KHR:
    case XR_TYPE_GRAPHICS_BINDING_OPENGL_WIN32_KHR:
    case XR_TYPE_GRAPHICS_BINDING_OPENGL_ES_ANDROID_KHR:
    case XR_TYPE_GRAPHICS_BINDING_VULKAN_KHR:
    case XR_TYPE_GRAPHICS_BINDING_D3D11_KHR:
    case XR_TYPE_GRAPHICS_BINDING_D3D12_KHR: return true;
    default: return false;
  }
}

XrResult create_session(XrInstance instance, const XrSessionCreateInfo* info, XrSession* out) {
  Instance* in = find(instance);
  if (in == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (!has_type(info, XR_TYPE_SESSION_CREATE_INFO) || out == nullptr || info->createFlags != 0)
    return XR_ERROR_VALIDATION_FAILURE;
  if (info->systemId != kSystemId) return XR_ERROR_SYSTEM_INVALID;
  bool has_gl = false;
  for (auto* s = static_cast<const XrBaseInStructure*>(info->next); s != nullptr; s = s->next) {
    if (is_other_graphics_binding(s->type)) return XR_ERROR_GRAPHICS_DEVICE_INVALID;
    if (s->type == XR_TYPE_GRAPHICS_BINDING_OPENGL_XLIB_KHR) {
      if (!in->opengl_enabled || has_gl) return XR_ERROR_GRAPHICS_DEVICE_INVALID;
      has_gl = true;
    }
  }
  if (has_gl && !in->gl_requirements_queried) return XR_ERROR_GRAPHICS_REQUIREMENTS_CALL_MISSING;
  if (!has_gl && !in->headless_enabled) return XR_ERROR_GRAPHICS_DEVICE_INVALID;
  if (in->config.refuse_session) {
    report("WEDGE_XR_REFUSE=session: xrCreateSession answers XR_ERROR_RUNTIME_FAILURE");
    return XR_ERROR_RUNTIME_FAILURE;
  }
  if (!in->sessions.empty()) return XR_ERROR_LIMIT_REACHED;  // one session at a time
  auto s = std::make_unique<Session>();
  s->instance = in;
  s->headless = !has_gl;
  Session* session = add(std::move(s));
  set_state(*session, XR_SESSION_STATE_IDLE);
  set_state(*session, XR_SESSION_STATE_READY);
  *out = handle_of<XrSession>(session->id);
  return XR_SUCCESS;
}

}  // namespace

void set_state(Session& s, XrSessionState state) {
  s.state = state;
  s.instance->events.push_state_changed(handle_of<XrSession>(s.id), state, s.now);
}

void begin_stopping(Session& s) {
  if (s.state == XR_SESSION_STATE_FOCUSED) set_state(s, XR_SESSION_STATE_VISIBLE);
  if (s.state == XR_SESSION_STATE_VISIBLE) set_state(s, XR_SESSION_STATE_SYNCHRONIZED);
  set_state(s, XR_SESSION_STATE_STOPPING);
  s.stopping = true;
}

void stop_at_recording_end(Session& s) {
  const std::optional<XrTime> end = s.instance->playback.end_time();
  if (s.running && !s.stopping && end && s.now > *end) begin_stopping(s);
}

XrResult xrCreateSession(XrInstance instance, const XrSessionCreateInfo* createInfo, XrSession* session) {
  return guarded("xrCreateSession", [&] { return create_session(instance, createInfo, session); });
}

XrResult xrDestroySession(XrSession session) {
  return guarded("xrDestroySession", [&]() -> XrResult {
    Session* s = find(session);
    if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
    destroy(s);
    return XR_SUCCESS;
  });
}

XrResult xrBeginSession(XrSession session, const XrSessionBeginInfo* beginInfo) {
  return guarded("xrBeginSession", [&]() -> XrResult {
    Session* s = find(session);
    if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (!has_type(beginInfo, XR_TYPE_SESSION_BEGIN_INFO)) return XR_ERROR_VALIDATION_FAILURE;
    if (const XrResult r = check_view_configuration(beginInfo->primaryViewConfigurationType); r != XR_SUCCESS) return r;
    if (s->running) return XR_ERROR_SESSION_RUNNING;
    if (s->state != XR_SESSION_STATE_READY) return XR_ERROR_SESSION_NOT_READY;
    s->running = true;
    s->stopping = false;
    set_state(*s, XR_SESSION_STATE_SYNCHRONIZED);
    set_state(*s, XR_SESSION_STATE_VISIBLE);
    set_state(*s, XR_SESSION_STATE_FOCUSED);
    return XR_SUCCESS;
  });
}

XrResult xrEndSession(XrSession session) {
  return guarded("xrEndSession", [&]() -> XrResult {
    Session* s = find(session);
    if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
    if (s->state != XR_SESSION_STATE_STOPPING) return XR_ERROR_SESSION_NOT_STOPPING;
    s->running = false;
    s->frame_waited = s->frame_begun = false;  // a frame in flight is discarded
    set_state(*s, XR_SESSION_STATE_IDLE);
    // The replay is over (or the app asked to leave): there is nothing to come back to.
    set_state(*s, XR_SESSION_STATE_EXITING);
    return XR_SUCCESS;
  });
}

XrResult xrRequestExitSession(XrSession session) {
  return guarded("xrRequestExitSession", [&]() -> XrResult {
    Session* s = find(session);
    if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
    if (!s->stopping) begin_stopping(*s);
    return XR_SUCCESS;
  });
}

}  // namespace wedge::xr_replay

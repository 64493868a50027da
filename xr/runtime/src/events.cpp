// The event queue (events.hpp) and xrPollEvent.
#include "events.hpp"

#include <algorithm>
#include <cstring>

#include "api.hpp"
#include "registry.hpp"

namespace wedge::xr_replay {

void EventQueue::push_state_changed(XrSession session, XrSessionState state, XrTime time) {
  XrEventDataBuffer buffer{};
  auto* e = reinterpret_cast<XrEventDataSessionStateChanged*>(&buffer);
  e->type = XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED;
  e->next = nullptr;
  e->session = session;
  e->state = state;
  e->time = time;
  queue_.emplace_back(session, buffer);
}

void EventQueue::push_profile_changed(XrSession session) {
  XrEventDataBuffer buffer{};
  auto* e = reinterpret_cast<XrEventDataInteractionProfileChanged*>(&buffer);
  e->type = XR_TYPE_EVENT_DATA_INTERACTION_PROFILE_CHANGED;
  e->next = nullptr;
  e->session = session;
  queue_.emplace_back(session, buffer);
}

bool EventQueue::pop(XrEventDataBuffer& out) {
  if (queue_.empty()) return false;
  // The app's buffer keeps its own next pointer; the event's fields are copied after the header.
  const XrEventDataBuffer& e = queue_.front().second;
  out.type = e.type;
  std::memcpy(out.varying, e.varying, sizeof(out.varying));
  queue_.pop_front();
  return true;
}

void EventQueue::drop_session(XrSession session) {
  queue_.erase(std::remove_if(queue_.begin(), queue_.end(), [&](const auto& e) { return e.first == session; }),
               queue_.end());
}

XrResult xrPollEvent(XrInstance instance, XrEventDataBuffer* eventData) {
  return guarded("xrPollEvent", [&]() -> XrResult {
    Instance* in = find(instance);
    if (in == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (eventData == nullptr || eventData->type != XR_TYPE_EVENT_DATA_BUFFER) return XR_ERROR_VALIDATION_FAILURE;
    return in->events.pop(*eventData) ? XR_SUCCESS : XR_EVENT_UNAVAILABLE;
  });
}

}  // namespace wedge::xr_replay

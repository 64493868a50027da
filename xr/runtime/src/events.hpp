// An instance's event queue, drained by xrPollEvent in the order the events happened.
#pragma once

#include <cstdint>
#include <deque>
#include <utility>

#include "xr_platform.hpp"

namespace wedge::xr_replay {

class EventQueue {
 public:
  void push_state_changed(XrSession session, XrSessionState state, XrTime time);
  void push_profile_changed(XrSession session);
  bool pop(XrEventDataBuffer& out);
  void drop_session(XrSession session);  // a destroyed session's events are never delivered

 private:
  std::deque<std::pair<XrSession, XrEventDataBuffer>> queue_;
};

}  // namespace wedge::xr_replay

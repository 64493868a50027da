// The session state machine (docs/xr-runtime.md, "Session"). The runtime moves a session and queues the
// matching XrEventDataSessionStateChanged (time: the session's frame time) in one step, so the state the
// entry points check is always the last one queued:
//   xrCreateSession            -> IDLE, READY
//   xrBeginSession             -> SYNCHRONIZED, VISIBLE, FOCUSED (at once, rendering or headless)
//   recording over / xrRequestExitSession -> VISIBLE, SYNCHRONIZED, STOPPING (the spec's way down)
//   xrEndSession (in STOPPING) -> IDLE, EXITING
#pragma once

#include "objects.hpp"

namespace wedge::xr_replay {

void set_state(Session& s, XrSessionState state);
// From wherever the running session is, down to STOPPING.
void begin_stopping(Session& s);
// Called after each xrWaitFrame: once the frame time is past the recording's last sample, the session stops.
void stop_at_recording_end(Session& s);

inline bool is_focused(const Session& s) { return s.state == XR_SESSION_STATE_FOCUSED; }

}  // namespace wedge::xr_replay

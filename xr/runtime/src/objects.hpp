// The objects behind the handles: instance, session, space, action set, action, swapchain. Each is owned by
// the registry (registry.hpp) and refers to its parent; a handle's value is the object's id, never reused,
// so a destroyed handle stays invalid forever.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include "clock.hpp"
#include "config.hpp"
#include "events.hpp"
#include "gl_functions.hpp"
#include "haptics.hpp"
#include "paths.hpp"
#include "playback.hpp"
#include "pose.hpp"
#include "profiles.hpp"
#include "xr_platform.hpp"

namespace wedge::xr_replay {

struct Instance;
struct Session;

struct Instance {
  uint64_t id = 0;
  Config config;
  Playback playback;
  bool headless_enabled = false;  // XR_MND_headless
  bool opengl_enabled = false;    // XR_KHR_opengl_enable
  bool timespec_enabled = false;  // XR_KHR_convert_timespec_time
  TimespecMap timespec;
  PathTable paths;
  EventQueue events;
  HapticsLog haptics;
  bool gl_requirements_queried = false;  // xrGetOpenGLGraphicsRequirementsKHR was called
  bool bindings_frozen = false;          // some session attached action sets: no more suggestions
  std::map<XrPath, std::vector<XrActionSuggestedBinding>> suggestions;  // profile -> its latest suggestion
  std::vector<uint64_t> sessions, action_sets;                           // children, for cascading destroys
};

struct ActionSet {
  uint64_t id = 0;
  Instance* instance = nullptr;
  std::string name, localized_name;
  uint32_t priority = 0;
  bool attached = false;  // attached to a session: immutable from then on
  std::vector<uint64_t> actions;
};

struct Action {
  uint64_t id = 0;
  ActionSet* set = nullptr;
  std::string name, localized_name;
  XrActionType type = XR_ACTION_TYPE_BOOLEAN_INPUT;
  std::vector<XrPath> subaction_paths;
};

// One action's last synced state for one filter (a subaction path, or XR_NULL_PATH for all of them).
struct ActionState {
  bool active = false;
  double value = 0.0;  // boolean (0 / 1), float, or a 2D input's x
  double y = 0.0;      // a 2D input's y
  bool changed = false;
  XrTime last_change = 0;
};

// An action as the session sees it once its set is attached: what it is bound to under the current profile.
// It outlives the app's action handle (the spec keeps attached actions working after xrDestroyAction).
struct BoundAction {
  uint64_t set_id = 0;
  XrActionType type = XR_ACTION_TYPE_BOOLEAN_INPUT;
  std::vector<XrPath> subaction_paths;
  std::vector<Source> sources;
  std::vector<XrPath> source_subaction;        // per source: its hand's user path atom
  std::map<XrPath, ActionState> states;        // filter -> last synced state
};

struct Session {
  uint64_t id = 0;
  Instance* instance = nullptr;
  bool headless = false;
  XrSessionState state = XR_SESSION_STATE_UNKNOWN;
  bool running = false;    // between xrBeginSession and xrEndSession
  bool stopping = false;   // STOPPING queued (recording over, or xrRequestExitSession)
  // Frame clock (clock.hpp): frames_waited counts xrWaitFrame calls; now is the latest predicted display time.
  uint64_t frames_waited = 0;
  XrTime now = kEpoch;
  bool frame_waited = false;  // an xrWaitFrame not yet consumed by xrBeginFrame
  bool frame_begun = false;   // an xrBeginFrame not yet ended
  uint64_t frames_submitted = 0;
  // Input.
  bool attached = false;
  std::vector<uint64_t> attached_sets;
  XrPath profile = XR_NULL_PATH;            // the current interaction profile of both hands
  std::map<uint64_t, BoundAction> actions;  // by action id
  std::map<uint64_t, XrPath> active_sets;   // set id -> subaction filter of the last xrSyncActions
  bool input_focused = false;               // the last xrSyncActions ran focused
  // Graphics.
  GlFunctions gl;  // resolved at the first xrCreateSwapchain, in the app's current context
  std::vector<uint64_t> spaces, swapchains;
};

struct Space {
  uint64_t id = 0;
  Session* session = nullptr;
  bool is_action = false;
  XrReferenceSpaceType reference = XR_REFERENCE_SPACE_TYPE_LOCAL;  // reference spaces
  uint64_t action = 0;                                              // action spaces: the pose action
  XrPath subaction = XR_NULL_PATH;
  Pose offset;  // poseInReferenceSpace / poseInActionSpace
};

struct Swapchain {
  uint64_t id = 0;
  Session* session = nullptr;
  XrSwapchainCreateInfo info{};
  std::vector<uint32_t> textures;  // GL names
  std::deque<uint32_t> acquired;   // acquired images, oldest first
  bool waited = false;             // the oldest acquired image has been waited
  uint32_t next_image = 0;
  int last_released = -1;
  bool ever_acquired = false;      // a static swapchain may be acquired once
};

}  // namespace wedge::xr_replay

// Test helpers over the real loader (xr_test_support.hpp).
#include "xr_test_support.hpp"

#include <openxr/openxr_reflection.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>

namespace xrtest {

XrTime frame_time(uint64_t n) { return kEpoch + std::llround(double(n) * 1e9 / 90.0); }
XrTime sample_time(double t_seconds) { return kEpoch + std::llround(t_seconds * 1e9); }

void runtime_env(std::initializer_list<std::pair<const char*, std::string>> vars) {
  for (const char* v : {"WEDGE_XR_REPLAY", "WEDGE_XR_EYE_SIZE", "WEDGE_XR_HAPTICS_LOG", "WEDGE_XR_FRAMES",
                        "WEDGE_XR_FRAMES_EVERY", "WEDGE_XR_REFUSE"})
    unsetenv(v);
  for (const auto& [name, value] : vars) setenv(name, value.c_str(), 1);
}

std::string temp_path(const std::string& name) {
  return std::string(WEDGE_XR_TEST_DIR) + "/" + std::to_string(getpid()) + "_" + name;
}

wedge::recordings::HandSample hand(double t, wedge::recordings::Hand which, Eigen::Vector3d position,
                                   Eigen::Quaterniond orientation, double squeeze, double trigger, uint32_t buttons,
                                   bool mode4d) {
  wedge::recordings::HandSample s;
  s.t = t;
  s.hand = which;
  s.pose.position = position;
  s.pose.orientation = orientation;
  s.squeeze = squeeze;
  s.trigger = trigger;
  s.buttons = buttons;
  s.mode4d = mode4d;
  return s;
}

std::string write_test_recording(const std::string& name, const wedge::recordings::Recording& r) {
  const std::string path = temp_path(name);
  wedge::recordings::write_recording(path, r);
  return path;
}

Instance::Instance(std::vector<const char*> extensions) {
  XrInstanceCreateInfo info = xr_struct<XrInstanceCreateInfo>(XR_TYPE_INSTANCE_CREATE_INFO);
  std::strcpy(info.applicationInfo.applicationName, "wedge_xr_runtime_tests");
  info.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.enabledExtensionNames = extensions.data();
  REQUIRE(xrCreateInstance(&info, &handle_) == XR_SUCCESS);
}

Instance::~Instance() {
  if (handle_ != XR_NULL_HANDLE) xrDestroyInstance(handle_);
}

XrSystemId Instance::system() const {
  XrSystemGetInfo info = xr_struct<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
  info.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
  XrSystemId id = XR_NULL_SYSTEM_ID;
  REQUIRE(xrGetSystem(handle_, &info, &id) == XR_SUCCESS);
  return id;
}

XrPath Instance::path(const char* s) const {
  XrPath p = XR_NULL_PATH;
  REQUIRE(xrStringToPath(handle_, s, &p) == XR_SUCCESS);
  return p;
}

std::string Instance::path_string(XrPath p) const {
  uint32_t n = 0;
  REQUIRE(xrPathToString(handle_, p, 0, &n, nullptr) == XR_SUCCESS);
  std::string s(n, '\0');
  REQUIRE(xrPathToString(handle_, p, n, &n, s.data()) == XR_SUCCESS);
  s.resize(n - 1);
  return s;
}

std::vector<XrEventDataBuffer> Instance::poll_events() const {
  std::vector<XrEventDataBuffer> out;
  while (true) {
    XrEventDataBuffer e = xr_struct<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
    const XrResult r = xrPollEvent(handle_, &e);
    REQUIRE((r == XR_SUCCESS || r == XR_EVENT_UNAVAILABLE));
    if (r == XR_EVENT_UNAVAILABLE) return out;
    out.push_back(e);
  }
}

HeadlessSession::HeadlessSession(const Instance& instance, bool begin) {
  XrSessionCreateInfo info = xr_struct<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
  info.systemId = instance.system();
  REQUIRE(xrCreateSession(instance.get(), &info, &handle_) == XR_SUCCESS);
  if (!begin) return;
  XrSessionBeginInfo b = xr_struct<XrSessionBeginInfo>(XR_TYPE_SESSION_BEGIN_INFO);
  b.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
  REQUIRE(xrBeginSession(handle_, &b) == XR_SUCCESS);
}

HeadlessSession::~HeadlessSession() {
  if (handle_ != XR_NULL_HANDLE) xrDestroySession(handle_);
}

XrFrameState HeadlessSession::wait_frame() const {
  XrFrameState state = xr_struct<XrFrameState>(XR_TYPE_FRAME_STATE);
  REQUIRE(xrWaitFrame(handle_, nullptr, &state) == XR_SUCCESS);
  return state;
}

XrSpace HeadlessSession::reference_space(XrReferenceSpaceType type) const {
  XrReferenceSpaceCreateInfo info = xr_struct<XrReferenceSpaceCreateInfo>(XR_TYPE_REFERENCE_SPACE_CREATE_INFO);
  info.referenceSpaceType = type;
  info.poseInReferenceSpace.orientation.w = 1.0f;
  XrSpace space = XR_NULL_HANDLE;
  REQUIRE(xrCreateReferenceSpace(handle_, &info, &space) == XR_SUCCESS);
  return space;
}

std::vector<XrSessionState> states_of(const std::vector<XrEventDataBuffer>& events) {
  std::vector<XrSessionState> out;
  for (const XrEventDataBuffer& e : events)
    if (e.type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED)
      out.push_back(reinterpret_cast<const XrEventDataSessionStateChanged&>(e).state);
  return out;
}

XrAction make_action(XrActionSet set, const char* name, XrActionType type, const std::vector<XrPath>& subactions) {
  XrActionCreateInfo info = xr_struct<XrActionCreateInfo>(XR_TYPE_ACTION_CREATE_INFO);
  std::strcpy(info.actionName, name);
  std::strcpy(info.localizedActionName, name);
  info.actionType = type;
  info.countSubactionPaths = uint32_t(subactions.size());
  info.subactionPaths = subactions.data();
  XrAction a = XR_NULL_HANDLE;
  REQUIRE(xrCreateAction(set, &info, &a) == XR_SUCCESS);
  return a;
}

TouchActions make_touch_actions(const Instance& instance) {
  TouchActions t;
  XrActionSetCreateInfo info = xr_struct<XrActionSetCreateInfo>(XR_TYPE_ACTION_SET_CREATE_INFO);
  std::strcpy(info.actionSetName, "hands");
  std::strcpy(info.localizedActionSetName, "Hands");
  REQUIRE(xrCreateActionSet(instance.get(), &info, &t.set) == XR_SUCCESS);
  t.left = instance.path("/user/hand/left");
  t.right = instance.path("/user/hand/right");
  const std::vector<XrPath> both{t.left, t.right};
  t.grip = make_action(t.set, "grip", XR_ACTION_TYPE_POSE_INPUT, both);
  t.aim = make_action(t.set, "aim", XR_ACTION_TYPE_POSE_INPUT, both);
  t.squeeze = make_action(t.set, "squeeze", XR_ACTION_TYPE_FLOAT_INPUT, both);
  t.trigger = make_action(t.set, "trigger", XR_ACTION_TYPE_FLOAT_INPUT, both);
  t.primary = make_action(t.set, "primary", XR_ACTION_TYPE_BOOLEAN_INPUT, both);
  t.secondary = make_action(t.set, "secondary", XR_ACTION_TYPE_BOOLEAN_INPUT, both);
  t.squeeze_click = make_action(t.set, "squeeze_click", XR_ACTION_TYPE_BOOLEAN_INPUT, both);
  t.thumbstick = make_action(t.set, "thumbstick", XR_ACTION_TYPE_VECTOR2F_INPUT, both);
  t.haptic = make_action(t.set, "haptic", XR_ACTION_TYPE_VIBRATION_OUTPUT, both);
  std::vector<XrActionSuggestedBinding> b;
  for (const char* side : {"left", "right"}) {
    const std::string u = std::string("/user/hand/") + side;
    const bool left = std::string(side) == "left";
    b.push_back({t.grip, instance.path((u + "/input/grip/pose").c_str())});
    b.push_back({t.aim, instance.path((u + "/input/aim/pose").c_str())});
    b.push_back({t.squeeze, instance.path((u + "/input/squeeze/value").c_str())});
    b.push_back({t.trigger, instance.path((u + "/input/trigger/value").c_str())});
    b.push_back({t.primary, instance.path((u + (left ? "/input/x/click" : "/input/a/click")).c_str())});
    b.push_back({t.secondary, instance.path((u + (left ? "/input/y/click" : "/input/b/click")).c_str())});
    b.push_back({t.squeeze_click, instance.path((u + "/input/squeeze").c_str())});  // identifier only
    b.push_back({t.thumbstick, instance.path((u + "/input/thumbstick").c_str())});
    b.push_back({t.haptic, instance.path((u + "/output/haptic").c_str())});
  }
  XrInteractionProfileSuggestedBinding s = xr_struct<XrInteractionProfileSuggestedBinding>(XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING);
  s.interactionProfile = instance.path("/interaction_profiles/oculus/touch_controller");
  s.countSuggestedBindings = uint32_t(b.size());
  s.suggestedBindings = b.data();
  REQUIRE(xrSuggestInteractionProfileBindings(instance.get(), &s) == XR_SUCCESS);
  return t;
}

void attach(XrSession session, XrActionSet set) {
  XrSessionActionSetsAttachInfo info = xr_struct<XrSessionActionSetsAttachInfo>(XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO);
  info.countActionSets = 1;
  info.actionSets = &set;
  REQUIRE(xrAttachSessionActionSets(session, &info) == XR_SUCCESS);
}

XrResult sync(XrSession session, XrActionSet set, XrPath subaction) {
  XrActiveActionSet active{set, subaction};
  XrActionsSyncInfo info = xr_struct<XrActionsSyncInfo>(XR_TYPE_ACTIONS_SYNC_INFO);
  info.countActiveActionSets = 1;
  info.activeActionSets = &active;
  return xrSyncActions(session, &info);
}

XrSpace action_space(XrSession session, XrAction action, XrPath subaction) {
  XrActionSpaceCreateInfo info = xr_struct<XrActionSpaceCreateInfo>(XR_TYPE_ACTION_SPACE_CREATE_INFO);
  info.action = action;
  info.subactionPath = subaction;
  info.poseInActionSpace.orientation.w = 1.0f;
  XrSpace space = XR_NULL_HANDLE;
  REQUIRE(xrCreateActionSpace(session, &info, &space) == XR_SUCCESS);
  return space;
}

XrSpaceLocation locate(XrSpace space, XrSpace base, XrTime time) {
  XrSpaceLocation location = xr_struct<XrSpaceLocation>(XR_TYPE_SPACE_LOCATION);
  REQUIRE(xrLocateSpace(space, base, time, &location) == XR_SUCCESS);
  return location;
}

const char* result_name(XrResult r) {
#define WEDGE_XR_TEST_CASE(name, value) \
  case name:                            \
    return #name;
  switch (r) {
    XR_LIST_ENUM_XrResult(WEDGE_XR_TEST_CASE) default : return "unknown XrResult";
  }
#undef WEDGE_XR_TEST_CASE
}

}  // namespace xrtest

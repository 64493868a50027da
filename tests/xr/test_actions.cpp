// The action system: paths, names, binding suggestions, the current profile, and the states the recording's
// squeeze, trigger and buttons give, with lastChangeTime at the sample where each value changed.
#include <cstring>

#include "xr_test_support.hpp"

using namespace xrtest;
using wedge::recordings::Hand;
using wedge::recordings::kButtonA;
using wedge::recordings::kButtonB;
using wedge::recordings::kButtonX;
using wedge::recordings::kButtonY;

namespace {

struct Bool {
  bool active, value, changed;
  XrTime last_change;
};
struct Float {
  bool active;
  float value;
  bool changed;
  XrTime last_change;
};

Bool get_bool(XrSession s, XrAction a, XrPath sub) {
  XrActionStateGetInfo info = xr_struct<XrActionStateGetInfo>(XR_TYPE_ACTION_STATE_GET_INFO);
  info.action = a;
  info.subactionPath = sub;
  XrActionStateBoolean st = xr_struct<XrActionStateBoolean>(XR_TYPE_ACTION_STATE_BOOLEAN);
  REQUIRE(xrGetActionStateBoolean(s, &info, &st) == XR_SUCCESS);
  return {st.isActive == XR_TRUE, st.currentState == XR_TRUE, st.changedSinceLastSync == XR_TRUE, st.lastChangeTime};
}

Float get_float(XrSession s, XrAction a, XrPath sub) {
  XrActionStateGetInfo info = xr_struct<XrActionStateGetInfo>(XR_TYPE_ACTION_STATE_GET_INFO);
  info.action = a;
  info.subactionPath = sub;
  XrActionStateFloat st = xr_struct<XrActionStateFloat>(XR_TYPE_ACTION_STATE_FLOAT);
  REQUIRE(xrGetActionStateFloat(s, &info, &st) == XR_SUCCESS);
  return {st.isActive == XR_TRUE, st.currentState, st.changedSinceLastSync == XR_TRUE, st.lastChangeTime};
}

// A synced state against what the recording says: its value, whether it changed since the previous sync,
// and the XrTime of the sample at which it became that value.
void expect(const Bool& b, bool value, bool changed, XrTime since) {
  CHECK(b.active);
  CHECK(b.value == value);
  CHECK(b.changed == changed);
  CHECK(b.last_change == since);
}
void expect(const Float& f, float value, bool changed, XrTime since) {
  CHECK(f.active);
  CHECK(f.value == value);
  CHECK(f.changed == changed);
  CHECK(f.last_change == since);
}

// The thumbstick (there, always at rest), then getters called wrongly: another type, a subaction path the
// action lacks, an atom never handed out.
void check_thumbstick_and_misuse(const Instance& instance, XrSession s, const TouchActions& t) {
  XrActionStateGetInfo info = xr_struct<XrActionStateGetInfo>(XR_TYPE_ACTION_STATE_GET_INFO);
  info.action = t.thumbstick;
  info.subactionPath = t.right;
  XrActionStateVector2f v = xr_struct<XrActionStateVector2f>(XR_TYPE_ACTION_STATE_VECTOR2F);
  REQUIRE(xrGetActionStateVector2f(s, &info, &v) == XR_SUCCESS);
  CHECK(v.isActive == XR_TRUE);
  CHECK(v.currentState.x == 0.0f);
  CHECK(v.currentState.y == 0.0f);
  XrActionStateFloat f = xr_struct<XrActionStateFloat>(XR_TYPE_ACTION_STATE_FLOAT);
  CHECK(xrGetActionStateFloat(s, &info, &f) == XR_ERROR_ACTION_TYPE_MISMATCH);
  info.action = t.squeeze;
  info.subactionPath = instance.path("/user/head");
  CHECK(xrGetActionStateFloat(s, &info, &f) == XR_ERROR_PATH_UNSUPPORTED);
  info.subactionPath = XrPath(123456);
  CHECK(xrGetActionStateFloat(s, &info, &f) == XR_ERROR_PATH_INVALID);
}

XrActionSet make_set(const Instance& instance, const char* name) {
  XrActionSetCreateInfo info = xr_struct<XrActionSetCreateInfo>(XR_TYPE_ACTION_SET_CREATE_INFO);
  std::strcpy(info.actionSetName, name);
  std::strcpy(info.localizedActionSetName, name);
  XrActionSet set = XR_NULL_HANDLE;
  REQUIRE(xrCreateActionSet(instance.get(), &info, &set) == XR_SUCCESS);
  return set;
}

XrResult suggest(const Instance& instance, const char* profile,
                 std::vector<std::pair<XrAction, const char*>> bindings) {
  std::vector<XrActionSuggestedBinding> b;
  for (const auto& [action, path] : bindings) b.push_back({action, instance.path(path)});
  XrInteractionProfileSuggestedBinding s = xr_struct<XrInteractionProfileSuggestedBinding>(XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING);
  s.interactionProfile = instance.path(profile);
  s.countSuggestedBindings = uint32_t(b.size());
  s.suggestedBindings = b.data();
  return xrSuggestInteractionProfileBindings(instance.get(), &s);
}

// Waits frames until the frame time is at least `t` seconds on the recording's clock; returns that frame time.
XrTime wait_until(const HeadlessSession& session, uint64_t& n, double t) {
  while (frame_time(n) < sample_time(t)) {
    session.wait_frame();
    ++n;
  }
  session.wait_frame();
  return frame_time(n++);
}

}  // namespace

TEST_CASE("xr runtime: squeeze, trigger and buttons follow the recording, lastChangeTime at the changing sample") {
  wedge::recordings::Recording r;
  r.source = "script";
  const Eigen::Vector3d p(0.2, 1.0, -0.3);
  const Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  r.hands = {hand(0.00, Hand::Right, p, q, 0.0, 0.0, 0),
             hand(0.05, Hand::Left, p, q, 0.0, 0.0, kButtonX),
             hand(0.10, Hand::Right, p, q, 0.3, 0.6, 0),
             hand(0.20, Hand::Right, p, q, 0.6, 0.6, kButtonA),
             hand(0.25, Hand::Left, p, q, 0.0, 0.0, kButtonX | kButtonY),
             hand(0.30, Hand::Right, p, q, 0.5, 0.6, kButtonA | kButtonB),
             hand(0.40, Hand::Right, p, q, 0.4, 0.6, kButtonB),
             hand(0.50, Hand::Right, p, q, 0.4, 0.6, 0, true)};
  runtime_env({{"WEDGE_XR_REPLAY", write_test_recording("buttons.jsonl", r)}});
  Instance instance;
  HeadlessSession session(instance, false);
  const TouchActions t = make_touch_actions(instance);
  attach(session.get(), t.set);
  const XrSession s = session.get();

  // Not focused yet: the sync says so and every action is inactive.
  CHECK(sync(s, t.set) == XR_SESSION_NOT_FOCUSED);
  CHECK_FALSE(get_float(s, t.squeeze, t.right).active);
  CHECK_FALSE(get_bool(s, t.primary, t.left).active);
  XrSessionBeginInfo begin = xr_struct<XrSessionBeginInfo>(XR_TYPE_SESSION_BEGIN_INFO);
  begin.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
  REQUIRE(xrBeginSession(s, &begin) == XR_SUCCESS);

  // Before any frame the sync samples kEpoch (recording time 0): the first right sample, all at rest.
  REQUIRE(sync(s, t.set) == XR_SUCCESS);
  expect(get_float(s, t.squeeze, t.right), 0.0f, false, kEpoch);
  expect(get_bool(s, t.primary, t.left), false, false, kEpoch);  // the left hand's first sample is at 0.05 s

  uint64_t n = 0;
  wait_until(session, n, 0.10);
  REQUIRE(sync(s, t.set) == XR_SUCCESS);
  expect(get_float(s, t.squeeze, t.right), 0.3f, true, sample_time(0.10));
  expect(get_float(s, t.trigger, t.right), 0.6f, true, sample_time(0.10));
  expect(get_bool(s, t.primary, t.left), true, true, sample_time(0.05));
  expect(get_bool(s, t.squeeze_click, t.right), false, false, kEpoch);  // 0.3: below the threshold

  wait_until(session, n, 0.20);
  REQUIRE(sync(s, t.set) == XR_SUCCESS);
  expect(get_bool(s, t.primary, t.right), true, true, sample_time(0.20));
  // /input/squeeze for a boolean action: squeeze/value through the threshold (on at >= 0.55).
  expect(get_bool(s, t.squeeze_click, t.right), true, true, sample_time(0.20));
  expect(get_bool(s, t.primary, t.left), true, false, sample_time(0.05));
  // Without a subaction path both hands are combined: the larger squeeze, either hand's button.
  CHECK(get_float(s, t.squeeze, XR_NULL_PATH).value == 0.6f);
  CHECK(get_bool(s, t.primary, XR_NULL_PATH).value);

  wait_until(session, n, 0.30);
  REQUIRE(sync(s, t.set) == XR_SUCCESS);
  expect(get_bool(s, t.squeeze_click, t.right), true, false, sample_time(0.20));  // 0.5: still on (hysteresis)
  expect(get_bool(s, t.secondary, t.right), true, true, sample_time(0.30));
  expect(get_bool(s, t.secondary, t.left), true, true, sample_time(0.25));
  expect(get_float(s, t.squeeze, t.right), 0.5f, true, sample_time(0.30));

  wait_until(session, n, 0.40);
  REQUIRE(sync(s, t.set) == XR_SUCCESS);
  expect(get_bool(s, t.squeeze_click, t.right), false, true, sample_time(0.40));  // 0.4: off
  expect(get_bool(s, t.primary, t.right), false, true, sample_time(0.40));
  expect(get_bool(s, t.secondary, t.right), true, false, sample_time(0.30));

  wait_until(session, n, 0.50);
  REQUIRE(sync(s, t.set) == XR_SUCCESS);
  expect(get_bool(s, t.primary, t.right), true, true, sample_time(0.50));  // the mode4d flag reads as A held
  expect(get_float(s, t.squeeze, t.right), 0.4f, false, sample_time(0.40));
  expect(get_float(s, t.trigger, t.right), 0.6f, false, sample_time(0.10));
  check_thumbstick_and_misuse(instance, s, t);
}

TEST_CASE("xr runtime: binding suggestions are checked against each profile, the current profile is Touch") {
  runtime_env();
  Instance instance;
  HeadlessSession session(instance);
  const XrActionSet set = make_set(instance, "game");
  const XrPath left = instance.path("/user/hand/left"), right = instance.path("/user/hand/right");
  const XrAction grab = make_action(set, "grab", XR_ACTION_TYPE_FLOAT_INPUT, {left, right});
  const XrAction pose = make_action(set, "pose", XR_ACTION_TYPE_POSE_INPUT, {left, right});
  const XrAction buzz = make_action(set, "buzz", XR_ACTION_TYPE_VIBRATION_OUTPUT, {left, right});

  // A path the profile does not have, an unknown profile, an atom never handed out.
  CHECK(suggest(instance, "/interaction_profiles/oculus/touch_controller", {{grab, "/user/hand/left/input/a/click"}}) ==
        XR_ERROR_PATH_UNSUPPORTED);
  CHECK(suggest(instance, "/interaction_profiles/htc/vive_controller", {{grab, "/user/hand/left/input/thumbstick/x"}}) ==
        XR_ERROR_PATH_UNSUPPORTED);
  CHECK(suggest(instance, "/interaction_profiles/acme/stick", {{grab, "/user/hand/left/input/select/click"}}) ==
        XR_ERROR_PATH_UNSUPPORTED);
  CHECK(suggest(instance, "/interaction_profiles/oculus/touch_controller", {{grab, "/user/hand/left/input"}}) ==
        XR_ERROR_PATH_UNSUPPORTED);
  XrActionSuggestedBinding bad{grab, XrPath(987654)};
  XrInteractionProfileSuggestedBinding s = xr_struct<XrInteractionProfileSuggestedBinding>(XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING);
  s.interactionProfile = instance.path("/interaction_profiles/khr/simple_controller");
  s.countSuggestedBindings = 1;
  s.suggestedBindings = &bad;
  CHECK(xrSuggestInteractionProfileBindings(instance.get(), &s) == XR_ERROR_PATH_INVALID);
  // Other profiles' valid suggestions are accepted.
  CHECK(suggest(instance, "/interaction_profiles/valve/index_controller",
                {{grab, "/user/hand/left/input/squeeze/force"}, {pose, "/user/hand/right/input/grip/pose"},
                 {buzz, "/user/hand/right/output/haptic"}}) == XR_SUCCESS);
  CHECK(suggest(instance, "/interaction_profiles/htc/vive_controller",
                {{grab, "/user/hand/left/input/trigger"}, {pose, "/user/hand/left/input/aim/pose"}}) == XR_SUCCESS);
  CHECK(suggest(instance, "/interaction_profiles/microsoft/motion_controller",
                {{grab, "/user/hand/right/input/squeeze/click"}}) == XR_SUCCESS);
  CHECK(suggest(instance, "/interaction_profiles/khr/simple_controller",
                {{grab, "/user/hand/right/input/select/click"}}) == XR_SUCCESS);
  CHECK(suggest(instance, "/interaction_profiles/oculus/touch_controller",
                {{grab, "/user/hand/left/input/squeeze/value"}, {grab, "/user/hand/right/input/squeeze"},
                 {pose, "/user/hand/right/input/grip/pose"}, {buzz, "/user/hand/right/output/haptic"}}) == XR_SUCCESS);

  XrInteractionProfileState profile = xr_struct<XrInteractionProfileState>(XR_TYPE_INTERACTION_PROFILE_STATE);
  CHECK(xrGetCurrentInteractionProfile(session.get(), left, &profile) == XR_ERROR_ACTIONSET_NOT_ATTACHED);
  instance.poll_events();
  attach(session.get(), set);
  const std::vector<XrEventDataBuffer> events = instance.poll_events();
  REQUIRE(events.size() == 1);
  CHECK(events[0].type == XR_TYPE_EVENT_DATA_INTERACTION_PROFILE_CHANGED);
  REQUIRE(xrGetCurrentInteractionProfile(session.get(), left, &profile) == XR_SUCCESS);
  CHECK(instance.path_string(profile.interactionProfile) == "/interaction_profiles/oculus/touch_controller");
  REQUIRE(xrGetCurrentInteractionProfile(session.get(), instance.path("/user/head"), &profile) == XR_SUCCESS);
  CHECK(profile.interactionProfile == XR_NULL_PATH);
  CHECK(xrGetCurrentInteractionProfile(session.get(), instance.path("/user/foot"), &profile) ==
        XR_ERROR_PATH_UNSUPPORTED);

  // Once attached: no more suggestions, no new actions in the set, no second attach.
  CHECK(suggest(instance, "/interaction_profiles/khr/simple_controller",
                {{grab, "/user/hand/left/input/select/click"}}) == XR_ERROR_ACTIONSETS_ALREADY_ATTACHED);
  XrActionCreateInfo late = xr_struct<XrActionCreateInfo>(XR_TYPE_ACTION_CREATE_INFO);
  std::strcpy(late.actionName, "late");
  std::strcpy(late.localizedActionName, "Late");
  late.actionType = XR_ACTION_TYPE_BOOLEAN_INPUT;
  XrAction a = XR_NULL_HANDLE;
  CHECK(xrCreateAction(set, &late, &a) == XR_ERROR_ACTIONSETS_ALREADY_ATTACHED);
  XrSessionActionSetsAttachInfo again = xr_struct<XrSessionActionSetsAttachInfo>(XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO);
  again.countActionSets = 1;
  again.actionSets = &set;
  CHECK(xrAttachSessionActionSets(session.get(), &again) == XR_ERROR_ACTIONSETS_ALREADY_ATTACHED);

  // The sources the Touch bindings resolved to: /input/squeeze for a float action is squeeze/value.
  XrBoundSourcesForActionEnumerateInfo e = xr_struct<XrBoundSourcesForActionEnumerateInfo>(XR_TYPE_BOUND_SOURCES_FOR_ACTION_ENUMERATE_INFO);
  e.action = grab;
  uint32_t count = 0;
  REQUIRE(xrEnumerateBoundSourcesForAction(session.get(), &e, 0, &count, nullptr) == XR_SUCCESS);
  REQUIRE(count == 2);
  std::vector<XrPath> sources(count);
  REQUIRE(xrEnumerateBoundSourcesForAction(session.get(), &e, count, &count, sources.data()) == XR_SUCCESS);
  CHECK(instance.path_string(sources[0]) == "/user/hand/left/input/squeeze/value");
  CHECK(instance.path_string(sources[1]) == "/user/hand/right/input/squeeze/value");
  XrInputSourceLocalizedNameGetInfo name = xr_struct<XrInputSourceLocalizedNameGetInfo>(XR_TYPE_INPUT_SOURCE_LOCALIZED_NAME_GET_INFO);
  name.sourcePath = sources[1];
  name.whichComponents = XR_INPUT_SOURCE_LOCALIZED_NAME_USER_PATH_BIT |
                         XR_INPUT_SOURCE_LOCALIZED_NAME_INTERACTION_PROFILE_BIT |
                         XR_INPUT_SOURCE_LOCALIZED_NAME_COMPONENT_BIT;
  REQUIRE(xrGetInputSourceLocalizedName(session.get(), &name, 0, &count, nullptr) == XR_SUCCESS);
  std::string text(count, '\0');
  REQUIRE(xrGetInputSourceLocalizedName(session.get(), &name, count, &count, text.data()) == XR_SUCCESS);
  CHECK(text.c_str() == std::string("Right Hand Oculus Touch Controller Squeeze"));
  name.whichComponents = 0;
  CHECK(xrGetInputSourceLocalizedName(session.get(), &name, 0, &count, nullptr) == XR_ERROR_VALIDATION_FAILURE);
}

TEST_CASE("xr runtime: simple_controller is the profile when only it was suggested, none when neither was") {
  wedge::recordings::Recording r;
  r.source = "script";
  r.hands = {hand(0.0, Hand::Right, {0, 1, 0}, {1, 0, 0, 0}, 0.0, 0.7), hand(0.1, Hand::Right, {0, 1, 0}, {1, 0, 0, 0}, 0.0, 0.5),
             hand(0.2, Hand::Right, {0, 1, 0}, {1, 0, 0, 0}, 0.0, 0.2)};
  const std::string path = write_test_recording("simple.jsonl", r);
  for (bool suggest_simple : {true, false}) {
    INFO("simple_controller suggested: " << suggest_simple);
    runtime_env({{"WEDGE_XR_REPLAY", path}});
    Instance instance;
    HeadlessSession session(instance);
    const XrActionSet set = make_set(instance, "game");
    const XrPath right = instance.path("/user/hand/right");
    const XrAction select = make_action(set, "select", XR_ACTION_TYPE_BOOLEAN_INPUT, {right});
    if (suggest_simple)
      REQUIRE(suggest(instance, "/interaction_profiles/khr/simple_controller",
                      {{select, "/user/hand/right/input/select/click"}}) == XR_SUCCESS);
    REQUIRE(suggest(instance, "/interaction_profiles/htc/vive_controller",
                    {{select, "/user/hand/right/input/trigger/click"}}) == XR_SUCCESS);
    instance.poll_events();
    attach(session.get(), set);
    CHECK(instance.poll_events().size() == (suggest_simple ? 1u : 0u));
    XrInteractionProfileState profile = xr_struct<XrInteractionProfileState>(XR_TYPE_INTERACTION_PROFILE_STATE);
    REQUIRE(xrGetCurrentInteractionProfile(session.get(), right, &profile) == XR_SUCCESS);
    REQUIRE(sync(session.get(), set) == XR_SUCCESS);
    const Bool at0 = get_bool(session.get(), select, right);
    if (!suggest_simple) {
      CHECK(profile.interactionProfile == XR_NULL_PATH);
      CHECK_FALSE(at0.active);  // nothing of the Touch pair is bound
      continue;
    }
    CHECK(instance.path_string(profile.interactionProfile) == "/interaction_profiles/khr/simple_controller");
    CHECK(at0.active);
    CHECK(at0.value);  // select/click is the trigger through the threshold: 0.7 is on
    CHECK_FALSE(at0.changed);  // the first sync that finds an action active reports no change
    CHECK(at0.last_change == kEpoch);
    uint64_t n = 0;
    wait_until(session, n, 0.1);
    REQUIRE(sync(session.get(), set) == XR_SUCCESS);
    CHECK(get_bool(session.get(), select, right).value);  // 0.5: still on (hysteresis)
    wait_until(session, n, 0.2);
    REQUIRE(sync(session.get(), set) == XR_SUCCESS);
    const Bool off = get_bool(session.get(), select, right);
    CHECK_FALSE(off.value);
    CHECK(off.changed);
    CHECK(off.last_change == sample_time(0.2));
  }
}

TEST_CASE("xr runtime: path strings, action set and action names are validated") {
  runtime_env();
  Instance instance;
  XrPath p = XR_NULL_PATH;
  for (const char* bad : {"", "user/hand/left", "/user/hand/", "/user//hand", "/User/hand", "/user/./x", "/user/..",
                          "/user/hand left", "/"}) {
    INFO("'" << bad << "'");
    CHECK(xrStringToPath(instance.get(), bad, &p) == XR_ERROR_PATH_FORMAT_INVALID);
  }
  const XrPath a = instance.path("/user/hand/left/input/x.y_z-1/click");
  CHECK(instance.path("/user/hand/left/input/x.y_z-1/click") == a);
  CHECK(instance.path_string(a) == "/user/hand/left/input/x.y_z-1/click");
  uint32_t n = 0;
  char small[4];
  CHECK(xrPathToString(instance.get(), a, sizeof(small), &n, small) == XR_ERROR_SIZE_INSUFFICIENT);
  CHECK(n == std::strlen("/user/hand/left/input/x.y_z-1/click") + 1);
  CHECK(xrPathToString(instance.get(), XrPath(99999), 0, &n, nullptr) == XR_ERROR_PATH_INVALID);

  XrActionSetCreateInfo info = xr_struct<XrActionSetCreateInfo>(XR_TYPE_ACTION_SET_CREATE_INFO);
  XrActionSet set = XR_NULL_HANDLE;
  std::strcpy(info.localizedActionSetName, "Game");
  CHECK(xrCreateActionSet(instance.get(), &info, &set) == XR_ERROR_NAME_INVALID);
  std::strcpy(info.actionSetName, "Game");
  CHECK(xrCreateActionSet(instance.get(), &info, &set) == XR_ERROR_PATH_FORMAT_INVALID);
  std::strcpy(info.actionSetName, "game");
  info.localizedActionSetName[0] = '\0';
  CHECK(xrCreateActionSet(instance.get(), &info, &set) == XR_ERROR_LOCALIZED_NAME_INVALID);
  std::strcpy(info.localizedActionSetName, "Game");
  REQUIRE(xrCreateActionSet(instance.get(), &info, &set) == XR_SUCCESS);
  XrActionSet other = XR_NULL_HANDLE;
  CHECK(xrCreateActionSet(instance.get(), &info, &other) == XR_ERROR_NAME_DUPLICATED);
  std::strcpy(info.actionSetName, "game2");
  CHECK(xrCreateActionSet(instance.get(), &info, &other) == XR_ERROR_LOCALIZED_NAME_DUPLICATED);

  XrActionCreateInfo ai = xr_struct<XrActionCreateInfo>(XR_TYPE_ACTION_CREATE_INFO);
  std::strcpy(ai.actionName, "grab");
  std::strcpy(ai.localizedActionName, "Grab");
  ai.actionType = XrActionType(99);
  XrAction action = XR_NULL_HANDLE;
  CHECK(xrCreateAction(set, &ai, &action) == XR_ERROR_VALIDATION_FAILURE);
  ai.actionType = XR_ACTION_TYPE_FLOAT_INPUT;
  const XrPath middle = instance.path("/user/hand/middle"), left = instance.path("/user/hand/left");
  ai.countSubactionPaths = 1;
  ai.subactionPaths = &middle;
  CHECK(xrCreateAction(set, &ai, &action) == XR_ERROR_PATH_UNSUPPORTED);
  const XrPath twice[] = {left, left};
  ai.countSubactionPaths = 2;
  ai.subactionPaths = twice;
  CHECK(xrCreateAction(set, &ai, &action) == XR_ERROR_PATH_UNSUPPORTED);
  const XrPath never = XrPath(424242);
  ai.countSubactionPaths = 1;
  ai.subactionPaths = &never;
  CHECK(xrCreateAction(set, &ai, &action) == XR_ERROR_PATH_INVALID);
  ai.subactionPaths = &left;
  REQUIRE(xrCreateAction(set, &ai, &action) == XR_SUCCESS);
  CHECK(xrCreateAction(set, &ai, &action) == XR_ERROR_NAME_DUPLICATED);
}

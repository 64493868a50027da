#include "wedge/xr/controllers.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "wedge/xr/check.hpp"

namespace wedge::xr {

namespace {

constexpr const char* kHandPaths[input::kHandCount] = {"/user/hand/left", "/user/hand/right"};

// One suggested binding: an action (by name) and a path under /user/hand/{left,right}; `hands` says on
// which (both, or only one).
struct Binding {
  const char* action;
  const char* path;  // after /user/hand/<side>
  int hands = 3;     // bit 0 left, bit 1 right
};
struct Profile {
  const char* path;
  std::vector<Binding> bindings;
};

constexpr int kLeft = 1, kRight = 2;

// What each controller's buttons do (docs/xr.md, "Controls").
const std::vector<Profile>& profiles() {
  static const std::vector<Profile> table = {
      {"/interaction_profiles/khr/simple_controller",
       {{"grip_pose", "/input/grip/pose"},
        {"aim_pose", "/input/aim/pose"},
        {"grab", "/input/select/click"},
        {"mode_4d", "/input/menu/click"},
        {"haptic", "/output/haptic"}}},
      {"/interaction_profiles/oculus/touch_controller",
       {{"grip_pose", "/input/grip/pose"},
        {"aim_pose", "/input/aim/pose"},
        {"grab", "/input/squeeze/value"},
        {"trigger", "/input/trigger/value"},
        {"slice", "/input/thumbstick/y"},
        {"mode_4d", "/input/x/click", kLeft},
        {"mode_4d", "/input/a/click", kRight},
        {"reset", "/input/menu/click", kLeft},
        {"haptic", "/output/haptic"}}},
      {"/interaction_profiles/valve/index_controller",
       {{"grip_pose", "/input/grip/pose"},
        {"aim_pose", "/input/aim/pose"},
        {"grab", "/input/squeeze/value"},
        {"trigger", "/input/trigger/value"},
        {"slice", "/input/thumbstick/y"},
        {"mode_4d", "/input/a/click"},
        {"reset", "/input/b/click", kLeft},
        {"haptic", "/output/haptic"}}},
      {"/interaction_profiles/htc/vive_controller",
       {{"grip_pose", "/input/grip/pose"},
        {"aim_pose", "/input/aim/pose"},
        {"grab", "/input/squeeze/click"},
        {"trigger", "/input/trigger/value"},
        {"slice", "/input/trackpad/y"},
        {"mode_4d", "/input/menu/click"},
        {"haptic", "/output/haptic"}}},
      {"/interaction_profiles/microsoft/motion_controller",
       {{"grip_pose", "/input/grip/pose"},
        {"aim_pose", "/input/aim/pose"},
        {"grab", "/input/squeeze/click"},
        {"trigger", "/input/trigger/value"},
        {"slice", "/input/thumbstick/y"},
        {"mode_4d", "/input/trackpad/click"},
        {"reset", "/input/menu/click", kLeft},
        {"haptic", "/output/haptic"}}},
  };
  return table;
}

input::Pose to_pose(const XrPosef& p) {
  input::Pose out;
  out.position = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  out.orientation = Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z);
  out.orientation.normalize();  // (a float quaternion is unit only to about 1e-7)
  return out;
}

}  // namespace

Controllers::Controllers(const Instance& instance, const Session& session, Log log)
    : instance_(instance), session_(session), log_(std::move(log)) {
  for (int k = 0; k < input::kHandCount; ++k) hands_[std::size_t(k)].path = instance.path(kHandPaths[k]);
  XrActionSetCreateInfo set{XR_TYPE_ACTION_SET_CREATE_INFO};
  std::strcpy(set.actionSetName, "wedge");
  std::strcpy(set.localizedActionSetName, "Wedge");
  check(instance.handle(), xrCreateActionSet(instance.handle(), &set, &set_), "xrCreateActionSet");
  grip_ = make_action("grip_pose", "Hand (grip) pose", XR_ACTION_TYPE_POSE_INPUT);
  aim_ = make_action("aim_pose", "Pointer (aim) pose", XR_ACTION_TYPE_POSE_INPUT);
  grab_ = make_action("grab", "Grab", XR_ACTION_TYPE_FLOAT_INPUT);
  trigger_ = make_action("trigger", "Trigger", XR_ACTION_TYPE_FLOAT_INPUT);
  mode4d_ = make_action("mode_4d", "Turn into w (4D mode)", XR_ACTION_TYPE_BOOLEAN_INPUT);
  slice_ = make_action("slice", "Move the slice along w", XR_ACTION_TYPE_FLOAT_INPUT);
  reset_ = make_action("reset", "Reset the scene", XR_ACTION_TYPE_BOOLEAN_INPUT);
  haptic_ = make_action("haptic", "Collision feedback", XR_ACTION_TYPE_VIBRATION_OUTPUT);
  suggest_bindings();

  for (Hand& h : hands_) {
    XrActionSpaceCreateInfo space{XR_TYPE_ACTION_SPACE_CREATE_INFO};
    space.subactionPath = h.path;
    space.poseInActionSpace.orientation.w = 1.0f;
    space.action = grip_;
    check(instance.handle(), xrCreateActionSpace(session.handle(), &space, &h.grip), "xrCreateActionSpace(grip)");
    space.action = aim_;
    check(instance.handle(), xrCreateActionSpace(session.handle(), &space, &h.aim), "xrCreateActionSpace(aim)");
  }
  XrSessionActionSetsAttachInfo attach{XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO};
  attach.countActionSets = 1;
  attach.actionSets = &set_;
  check(instance.handle(), xrAttachSessionActionSets(session.handle(), &attach), "xrAttachSessionActionSets");
}

Controllers::~Controllers() {
  for (Hand& h : hands_) {
    if (h.grip != XR_NULL_HANDLE) xrDestroySpace(h.grip);
    if (h.aim != XR_NULL_HANDLE) xrDestroySpace(h.aim);
  }
  if (set_ != XR_NULL_HANDLE) xrDestroyActionSet(set_);  // (destroys its actions)
}

XrAction Controllers::make_action(const char* name, const char* localized, XrActionType type) {
  std::array<XrPath, input::kHandCount> paths{hands_[0].path, hands_[1].path};
  XrActionCreateInfo info{XR_TYPE_ACTION_CREATE_INFO};
  std::strcpy(info.actionName, name);
  std::strcpy(info.localizedActionName, localized);
  info.actionType = type;
  info.countSubactionPaths = std::uint32_t(paths.size());
  info.subactionPaths = paths.data();
  XrAction action = XR_NULL_HANDLE;
  check(instance_.handle(), xrCreateAction(set_, &info, &action), (std::string("xrCreateAction(") + name + ")").c_str());
  by_name_[name] = action;
  return action;
}

// Each profile's bindings in one suggestion. A runtime refuses a whole suggestion for one path it does not
// know; then each binding is tried alone to find the ones it refuses, and the rest are suggested again.
void Controllers::suggest_bindings() {
  for (const Profile& profile : profiles()) {
    std::vector<XrActionSuggestedBinding> bindings;
    std::vector<std::string> names;
    for (const Binding& b : profile.bindings)
      for (int k = 0; k < input::kHandCount; ++k) {
        if (!(b.hands & (1 << k))) continue;
        const std::string path = std::string(kHandPaths[k]) + b.path;
        XrPath p = XR_NULL_PATH;
        if (XR_FAILED(xrStringToPath(instance_.handle(), path.c_str(), &p))) {
          log_(std::string(profile.path) + ": path " + path + " refused by xrStringToPath; binding dropped");
          continue;
        }
        bindings.push_back({by_name_.at(b.action), p});
        names.push_back(path);
      }
    const XrPath profile_path = instance_.path(profile.path);
    auto suggest = [&](const std::vector<XrActionSuggestedBinding>& list) {
      XrInteractionProfileSuggestedBinding s{XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING};
      s.interactionProfile = profile_path;
      s.countSuggestedBindings = std::uint32_t(list.size());
      s.suggestedBindings = list.data();
      return xrSuggestInteractionProfileBindings(instance_.handle(), &s);
    };
    XrResult r = suggest(bindings);
    if (XR_SUCCEEDED(r)) continue;
    std::vector<XrActionSuggestedBinding> kept;
    for (std::size_t i = 0; i < bindings.size(); ++i) {
      const XrResult alone = suggest({bindings[i]});
      if (XR_SUCCEEDED(alone))
        kept.push_back(bindings[i]);
      else
        log_(std::string(profile.path) + ": binding " + names[i] + " refused (" + result_name(instance_.handle(), alone) +
             "); the profile's other bindings kept");
    }
    r = kept.empty() ? r : suggest(kept);
    if (XR_FAILED(r))
      log_(std::string(profile.path) + ": bindings refused (" + result_name(instance_.handle(), r) + "); profile unused");
  }
}

void Controllers::sync() {
  focused_ = session_.focused();
  if (focused_) {
    XrActiveActionSet active{set_, XR_NULL_PATH};
    XrActionsSyncInfo info{XR_TYPE_ACTIONS_SYNC_INFO};
    info.countActiveActionSets = 1;
    info.activeActionSets = &active;
    const XrResult r = check(instance_.handle(), xrSyncActions(session_.handle(), &info), "xrSyncActions");
    focused_ = r != XR_SESSION_NOT_FOCUSED;
  }
  read_states();
}

void Controllers::read_states() {
  const XrInstance inst = instance_.handle();
  for (Hand& h : hands_) {
    XrActionStateGetInfo get{XR_TYPE_ACTION_STATE_GET_INFO};
    get.subactionPath = h.path;
    auto sample_float = [&](XrAction action, Sampled& s) {
      XrActionStateFloat st{XR_TYPE_ACTION_STATE_FLOAT};
      get.action = action;
      if (focused_) check(inst, xrGetActionStateFloat(session_.handle(), &get, &st), "xrGetActionStateFloat");
      s.before = s.now;
      s.now = st.isActive ? std::clamp(double(st.currentState), 0.0, 1.0) : 0.0;
      s.changed = st.isActive && st.changedSinceLastSync ? st.lastChangeTime : 0;
    };
    auto sample_bool = [&](XrAction action, Sampled& s) {
      XrActionStateBoolean st{XR_TYPE_ACTION_STATE_BOOLEAN};
      get.action = action;
      if (focused_) check(inst, xrGetActionStateBoolean(session_.handle(), &get, &st), "xrGetActionStateBoolean");
      s.before = s.now;
      s.now = st.isActive && st.currentState ? 1.0 : 0.0;
      s.changed = st.isActive && st.changedSinceLastSync ? st.lastChangeTime : 0;
    };
    sample_float(grab_, h.grab);
    sample_float(trigger_, h.trigger);
    sample_bool(mode4d_, h.mode4d);
    XrActionStateFloat slice{XR_TYPE_ACTION_STATE_FLOAT};
    get.action = slice_;
    if (focused_) check(inst, xrGetActionStateFloat(session_.handle(), &get, &slice), "xrGetActionStateFloat");
    h.slice = slice.isActive ? std::clamp(double(slice.currentState), -1.0, 1.0) : 0.0;
    XrActionStateBoolean reset{XR_TYPE_ACTION_STATE_BOOLEAN};
    get.action = reset_;
    if (focused_) check(inst, xrGetActionStateBoolean(session_.handle(), &get, &reset), "xrGetActionStateBoolean");
    h.reset_was = h.reset;
    h.reset = reset.isActive && reset.currentState;
    XrActionStatePose pose{XR_TYPE_ACTION_STATE_POSE};
    get.action = grip_;
    if (focused_) check(inst, xrGetActionStatePose(session_.handle(), &get, &pose), "xrGetActionStatePose");
    h.pose_active = pose.isActive;
  }
}

std::optional<input::Pose> Controllers::locate(XrSpace space, XrTime t) const {
  XrSpaceLocation loc{XR_TYPE_SPACE_LOCATION};
  check(instance_.handle(), xrLocateSpace(space, session_.space(), t, &loc), "xrLocateSpace");
  const XrSpaceLocationFlags both = XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT;
  if ((loc.locationFlags & both) != both) return std::nullopt;
  return to_pose(loc.pose);
}

input::HandInput Controllers::hand_at(int hand, XrTime t) {
  Hand& h = hands_[std::size_t(hand)];
  std::optional<input::Pose> pose;
  if (h.pose_active) pose = locate(h.grip, t);
  if (pose) {
    h.ever = true;
    h.last = *pose;
    h.last_valid = t;
  }
  input::HandInput in;
  if (!h.ever) return in;  // never seen: not tracked
  in.tracked = true;
  in.position = h.last.position;
  in.orientation = h.last.orientation;
  if (!pose && t - h.last_valid > kMaxGap) return in;  // lost too long: held still, nothing pressed
  in.squeeze = h.grab.at(t);
  in.trigger = h.trigger.at(t);
  in.mode4d = h.mode4d.at(t) > 0.5;
  if (in.mode4d) in.buttons = hand == 1 ? input::kButtonA : input::kButtonX;
  return in;
}

std::optional<input::Pose> Controllers::head_at(XrTime t) const { return locate(session_.view_space(), t); }

std::optional<input::Pose> Controllers::aim_at(int hand, XrTime t) const {
  const Hand& h = hands_[std::size_t(hand)];
  return h.pose_active ? locate(h.aim, t) : std::nullopt;
}

double Controllers::slice_rate() const {
  const double l = hands_[0].slice, r = hands_[1].slice;
  return std::abs(l) > std::abs(r) ? l : r;
}

bool Controllers::reset_pressed() const {
  return std::any_of(hands_.begin(), hands_.end(), [](const Hand& h) { return h.reset && !h.reset_was; });
}

void Controllers::pulse(int hand, double amplitude, double duration, double frequency) {
  XrHapticVibration v{XR_TYPE_HAPTIC_VIBRATION};
  v.amplitude = float(std::clamp(amplitude, 0.0, 1.0));
  v.duration = XrDuration(std::llround(duration * 1e9));
  v.frequency = frequency > 0.0 ? float(frequency) : XR_FREQUENCY_UNSPECIFIED;
  XrHapticActionInfo info{XR_TYPE_HAPTIC_ACTION_INFO};
  info.action = haptic_;
  info.subactionPath = hands_[std::size_t(hand)].path;
  const XrResult r =
      xrApplyHapticFeedback(session_.handle(), &info, reinterpret_cast<const XrHapticBaseHeader*>(&v));
  if (r != XR_SUCCESS && !haptic_failures_[r]) {  // (some runtimes drop haptics before the first sync: go on)
    haptic_failures_[r] = true;
    log_(std::string("xrApplyHapticFeedback on ") + kHandPaths[hand] + ": " + result_name(instance_.handle(), r) +
         " (logged once; pulses go on)");
  }
}

void Controllers::log_profiles() const {
  for (int k = 0; k < input::kHandCount; ++k) {
    XrInteractionProfileState state{XR_TYPE_INTERACTION_PROFILE_STATE};
    const XrResult r =
        xrGetCurrentInteractionProfile(session_.handle(), hands_[std::size_t(k)].path, &state);
    if (XR_FAILED(r)) {
      log_(std::string(kHandPaths[k]) + ": xrGetCurrentInteractionProfile: " + result_name(instance_.handle(), r));
      continue;
    }
    log_(std::string(kHandPaths[k]) + ": " + instance_.path_string(state.interactionProfile));
  }
}

}  // namespace wedge::xr

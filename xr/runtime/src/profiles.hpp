// Interaction profiles as data (OpenXR 1.0, "Interaction Profile Paths"), and the binding rules of the spec:
// which input source paths a profile has, how a path naming only an identifier (/input/squeeze) picks its
// component for an action's type, and which type conversions exist. The device is an Oculus Touch pair;
// khr/simple_controller is what it also answers to. The other profiles are only checked (their suggested
// bindings are validated and kept) since no device of theirs is ever connected.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "playback.hpp"
#include "xr_platform.hpp"

namespace wedge::xr_replay {

enum class ComponentType : uint8_t { Boolean, Float, Axis, Pose, Haptic };  // Axis: x or y of a 2D input

struct Component {
  std::string_view path;  // below the top-level user path, e.g. "input/squeeze/value", "output/haptic"
  ComponentType type;
  Channel channel = Channel::Zero;  // what the Touch pair reads there (Touch and simple_controller only)
};

struct ProfileGroup {  // components shared by some top-level user paths
  std::vector<std::string_view> users;
  std::vector<Component> components;
};

struct InteractionProfile {
  std::string_view path;  // "/interaction_profiles/oculus/touch_controller"
  std::string_view name;  // for xrGetInputSourceLocalizedName
  std::vector<ProfileGroup> groups;
};

inline constexpr std::string_view kTouchProfile = "/interaction_profiles/oculus/touch_controller";
inline constexpr std::string_view kSimpleProfile = "/interaction_profiles/khr/simple_controller";

const InteractionProfile* find_profile(std::string_view path);

// The top-level user paths of the spec (/user/hand/left, /user/hand/right, /user/head, /user/gamepad,
// /user/treadmill): the only subaction paths there are.
bool is_top_level_user_path(std::string_view path);
int hand_of(std::string_view user_path);  // kLeft, kRight, or -1

// A suggested binding split against its profile: user path, then either a whole component path or an
// identifier path ("input/squeeze", "input/thumbstick") whose component is picked later by action type.
struct BindingTarget {
  std::string user;
  std::string identifier;  // "input/squeeze"; for outputs the whole path ("output/haptic")
  const Component* component = nullptr;  // set when the path names one component
};
// False when the profile has no such user path or input source (XR_ERROR_PATH_UNSUPPORTED).
bool parse_binding(const InteractionProfile& profile, std::string_view binding, BindingTarget& out);

// What one binding of an action reads from the Touch pair.
enum class SourceKind : uint8_t { Value, Vector2, GripPose, AimPose, Haptic };
struct Source {
  int hand = kLeft;
  SourceKind kind = SourceKind::Value;
  Channel channel = Channel::Zero;  // for Value (a boolean action reads the *AsBool channel of an analog input)
  std::string path;                 // the input source path it resolved to, e.g. /user/hand/right/input/squeeze/value
  const Component* component = nullptr;
};
// Resolves a binding of an action of `type` (Touch or simple_controller). False when the binding does not
// apply: no conversion between the types exists (a pose on a button), or the user path is not a hand.
bool resolve_binding(const InteractionProfile& profile, const BindingTarget& target, XrActionType type, Source& out);

// "Right Hand", "Oculus Touch Controller", "Squeeze" ... for xrGetInputSourceLocalizedName.
std::string user_path_name(std::string_view user);
std::string component_name(std::string_view component_path);

}  // namespace wedge::xr_replay

// The interaction profile table and the spec's binding rules (profiles.hpp).
#include "profiles.hpp"

#include <algorithm>

namespace wedge::xr_replay {

namespace {

using T = ComponentType;
using C = Channel;

constexpr std::string_view kLeftHand = "/user/hand/left", kRightHand = "/user/hand/right";

// 2D inputs: the identifier with its x and y axes, read as 0 (the recordings have no thumbsticks).
void add_2d(std::vector<Component>& v, std::string_view x, std::string_view y) {
  v.push_back({x, T::Axis});
  v.push_back({y, T::Axis});
}

// The Touch pair as the profiles name it (OpenXR 1.0, "Oculus Touch Controller Profile").
InteractionProfile touch() {
  ProfileGroup left{{kLeftHand},
                    {{"input/x/click", T::Boolean, C::PrimaryClick}, {"input/x/touch", T::Boolean, C::PrimaryTouch},
                     {"input/y/click", T::Boolean, C::SecondaryClick}, {"input/y/touch", T::Boolean, C::SecondaryTouch},
                     {"input/menu/click", T::Boolean}}};
  ProfileGroup right{{kRightHand},
                     {{"input/a/click", T::Boolean, C::PrimaryClick}, {"input/a/touch", T::Boolean, C::PrimaryTouch},
                      {"input/b/click", T::Boolean, C::SecondaryClick}, {"input/b/touch", T::Boolean, C::SecondaryTouch},
                      {"input/system/click", T::Boolean}}};
  ProfileGroup both{{kLeftHand, kRightHand},
                    {{"input/squeeze/value", T::Float, C::Squeeze}, {"input/trigger/value", T::Float, C::Trigger},
                     {"input/trigger/touch", T::Boolean, C::TriggerTouch}}};
  add_2d(both.components, "input/thumbstick/x", "input/thumbstick/y");
  both.components.insert(both.components.end(),
                         {{"input/thumbstick/click", T::Boolean}, {"input/thumbstick/touch", T::Boolean},
                          {"input/thumbrest/touch", T::Boolean}, {"input/grip/pose", T::Pose},
                          {"input/aim/pose", T::Pose}, {"output/haptic", T::Haptic}});
  return {kTouchProfile, "Oculus Touch Controller", {left, right, both}};
}

// khr/simple_controller on the Touch pair: select is the index trigger (through the threshold).
InteractionProfile simple() {
  return {kSimpleProfile,
          "Khronos Simple Controller",
          {{{kLeftHand, kRightHand},
            {{"input/select/click", T::Boolean, C::TriggerAsBool}, {"input/menu/click", T::Boolean},
             {"input/grip/pose", T::Pose}, {"input/aim/pose", T::Pose}, {"output/haptic", T::Haptic}}}}};
}

// Profiles that are only validated: their components' types, no channels.
InteractionProfile hands_profile(std::string_view path, std::string_view name, std::vector<Component> c) {
  return {path, name, {{{kLeftHand, kRightHand}, std::move(c)}}};
}

std::vector<InteractionProfile> build_profiles() {
  std::vector<InteractionProfile> p{touch(), simple()};
  const Component grip{"input/grip/pose", T::Pose}, aim{"input/aim/pose", T::Pose}, haptic{"output/haptic", T::Haptic};
  std::vector<Component> vive{{"input/system/click", T::Boolean}, {"input/squeeze/click", T::Boolean},
                              {"input/menu/click", T::Boolean},   {"input/trigger/click", T::Boolean},
                              {"input/trigger/value", T::Float}};
  add_2d(vive, "input/trackpad/x", "input/trackpad/y");
  vive.insert(vive.end(), {{"input/trackpad/click", T::Boolean}, {"input/trackpad/touch", T::Boolean}, grip, aim, haptic});
  p.push_back(hands_profile("/interaction_profiles/htc/vive_controller", "HTC Vive Controller", vive));

  std::vector<Component> index{{"input/system/click", T::Boolean}, {"input/system/touch", T::Boolean},
                               {"input/a/click", T::Boolean},      {"input/a/touch", T::Boolean},
                               {"input/b/click", T::Boolean},      {"input/b/touch", T::Boolean},
                               {"input/squeeze/value", T::Float},  {"input/squeeze/force", T::Float},
                               {"input/trigger/click", T::Boolean}, {"input/trigger/value", T::Float},
                               {"input/trigger/touch", T::Boolean}};
  add_2d(index, "input/thumbstick/x", "input/thumbstick/y");
  index.insert(index.end(), {{"input/thumbstick/click", T::Boolean}, {"input/thumbstick/touch", T::Boolean}});
  add_2d(index, "input/trackpad/x", "input/trackpad/y");
  index.insert(index.end(), {{"input/trackpad/force", T::Float}, {"input/trackpad/touch", T::Boolean}, grip, aim, haptic});
  p.push_back(hands_profile("/interaction_profiles/valve/index_controller", "Valve Index Controller", index));

  std::vector<Component> ms{{"input/menu/click", T::Boolean}, {"input/squeeze/click", T::Boolean},
                            {"input/trigger/value", T::Float}};
  add_2d(ms, "input/thumbstick/x", "input/thumbstick/y");
  ms.push_back({"input/thumbstick/click", T::Boolean});
  add_2d(ms, "input/trackpad/x", "input/trackpad/y");
  ms.insert(ms.end(), {{"input/trackpad/click", T::Boolean}, {"input/trackpad/touch", T::Boolean}, grip, aim, haptic});
  p.push_back(hands_profile("/interaction_profiles/microsoft/motion_controller", "Windows Mixed Reality Controller", ms));

  std::vector<Component> daydream{{"input/select/click", T::Boolean}};
  add_2d(daydream, "input/trackpad/x", "input/trackpad/y");
  daydream.insert(daydream.end(), {{"input/trackpad/click", T::Boolean}, {"input/trackpad/touch", T::Boolean}, grip, aim});
  p.push_back(hands_profile("/interaction_profiles/google/daydream_controller", "Daydream Controller", daydream));

  std::vector<Component> go{{"input/system/click", T::Boolean}, {"input/trigger/click", T::Boolean},
                            {"input/back/click", T::Boolean}};
  add_2d(go, "input/trackpad/x", "input/trackpad/y");
  go.insert(go.end(), {{"input/trackpad/click", T::Boolean}, {"input/trackpad/touch", T::Boolean}, grip, aim});
  p.push_back(hands_profile("/interaction_profiles/oculus/go_controller", "Oculus Go Controller", go));

  p.push_back({"/interaction_profiles/htc/vive_pro",
               "HTC Vive Pro",
               {{{"/user/head"},
                 {{"input/system/click", T::Boolean}, {"input/volume_up/click", T::Boolean},
                  {"input/volume_down/click", T::Boolean}, {"input/mute_mic/click", T::Boolean}}}}});

  std::vector<Component> xbox;
  for (std::string_view b : {"input/menu/click", "input/view/click", "input/a/click", "input/b/click", "input/x/click",
                             "input/y/click", "input/dpad_down/click", "input/dpad_right/click", "input/dpad_up/click",
                             "input/dpad_left/click", "input/shoulder_left/click", "input/shoulder_right/click",
                             "input/thumbstick_left/click", "input/thumbstick_right/click"})
    xbox.push_back({b, T::Boolean});
  xbox.insert(xbox.end(), {{"input/trigger_left/value", T::Float}, {"input/trigger_right/value", T::Float}});
  add_2d(xbox, "input/thumbstick_left/x", "input/thumbstick_left/y");
  add_2d(xbox, "input/thumbstick_right/x", "input/thumbstick_right/y");
  xbox.insert(xbox.end(), {{"output/haptic_left", T::Haptic}, {"output/haptic_right", T::Haptic},
                           {"output/haptic_left_trigger", T::Haptic}, {"output/haptic_right_trigger", T::Haptic}});
  p.push_back({"/interaction_profiles/microsoft/xbox_controller", "Xbox Controller", {{{"/user/gamepad"}, xbox}}});
  return p;
}

const std::vector<InteractionProfile>& profiles() {
  static const std::vector<InteractionProfile> p = build_profiles();
  return p;
}

// The component `leaf` ("click", "value", "x", "pose") of an identifier, or null.
const Component* component_of(const ProfileGroup& g, std::string_view identifier, std::string_view leaf) {
  for (const Component& c : g.components)
    if (c.path.size() == identifier.size() + 1 + leaf.size() && c.path.substr(0, identifier.size()) == identifier &&
        c.path[identifier.size()] == '/' && c.path.substr(identifier.size() + 1) == leaf)
      return &c;
  return nullptr;
}

const ProfileGroup* group_of(const InteractionProfile& p, std::string_view user, std::string_view identifier) {
  for (const ProfileGroup& g : p.groups) {
    if (std::find(g.users.begin(), g.users.end(), user) == g.users.end()) continue;
    for (const Component& c : g.components) {
      // The component itself (an output), or its identifier: the path up to the last '/'.
      const std::size_t slash = c.path.rfind('/');
      if (c.path == identifier || (slash != std::string_view::npos && c.path.substr(0, slash) == identifier))
        return &g;
    }
  }
  return nullptr;
}

// A boolean action on an analog input reads it through the threshold.
Channel as_bool(Channel c) {
  switch (c) {
    case Channel::Squeeze: return Channel::SqueezeAsBool;
    case Channel::Trigger: return Channel::TriggerAsBool;
    default: return c;
  }
}

}  // namespace

const InteractionProfile* find_profile(std::string_view path) {
  for (const InteractionProfile& p : profiles())
    if (p.path == path) return &p;
  return nullptr;
}

bool is_top_level_user_path(std::string_view path) {
  return path == kLeftHand || path == kRightHand || path == "/user/head" || path == "/user/gamepad" ||
         path == "/user/treadmill";
}

int hand_of(std::string_view user_path) {
  return user_path == kLeftHand ? kLeft : user_path == kRightHand ? kRight : -1;
}

bool parse_binding(const InteractionProfile& profile, std::string_view binding, BindingTarget& out) {
  // The user path is the longest top-level user path that prefixes the binding.
  for (std::string_view user : {kLeftHand, kRightHand, std::string_view("/user/head"), std::string_view("/user/gamepad"),
                                std::string_view("/user/treadmill")}) {
    if (binding.size() <= user.size() + 1 || binding.substr(0, user.size()) != user || binding[user.size()] != '/')
      continue;
    const std::string_view rest = binding.substr(user.size() + 1);
    // Either a whole component ...
    for (const ProfileGroup& g : profile.groups) {
      if (std::find(g.users.begin(), g.users.end(), user) == g.users.end()) continue;
      for (const Component& c : g.components)
        if (c.path == rest) {
          out.user = std::string(user);
          out.component = &c;
          const std::size_t slash = rest.rfind('/');
          out.identifier = c.type == ComponentType::Haptic ? std::string(rest) : std::string(rest.substr(0, slash));
          return true;
        }
    }
    // ... or an identifier with components below it.
    if (group_of(profile, user, rest) == nullptr) return false;
    out.user = std::string(user);
    out.identifier = std::string(rest);
    out.component = nullptr;
    return true;
  }
  return false;
}

bool resolve_binding(const InteractionProfile& profile, const BindingTarget& target, XrActionType type, Source& out) {
  out.hand = hand_of(target.user);
  if (out.hand < 0) return false;
  const ProfileGroup* g = group_of(profile, target.user, target.identifier);
  if (g == nullptr) return false;
  const Component* c = target.component;
  if (c == nullptr) {  // the spec's choice of component for an identifier, by action type
    switch (type) {
      case XR_ACTION_TYPE_BOOLEAN_INPUT:
        c = component_of(*g, target.identifier, "click");
        if (c == nullptr) c = component_of(*g, target.identifier, "value");
        break;
      case XR_ACTION_TYPE_FLOAT_INPUT:
        c = component_of(*g, target.identifier, "value");
        if (c == nullptr) c = component_of(*g, target.identifier, "click");
        break;
      case XR_ACTION_TYPE_VECTOR2F_INPUT:
        if (component_of(*g, target.identifier, "x") == nullptr || component_of(*g, target.identifier, "y") == nullptr)
          return false;
        out.kind = SourceKind::Vector2;
        out.channel = Channel::Zero;
        out.component = component_of(*g, target.identifier, "x");
        out.path = target.user + "/" + target.identifier;
        return true;
      case XR_ACTION_TYPE_POSE_INPUT: c = component_of(*g, target.identifier, "pose"); break;
      default: return false;  // outputs always name their whole path
    }
    if (c == nullptr) return false;
  }
  out.component = c;
  out.path = target.user + "/" + std::string(c->path);
  out.channel = Channel::Zero;
  // Conversions: boolean <-> float both ways (analog through the threshold), an axis as a float; poses and
  // haptics only to their own type.
  switch (c->type) {
    case ComponentType::Boolean:
    case ComponentType::Float:
    case ComponentType::Axis:
      if (type != XR_ACTION_TYPE_BOOLEAN_INPUT && type != XR_ACTION_TYPE_FLOAT_INPUT) return false;
      out.kind = SourceKind::Value;
      out.channel = type == XR_ACTION_TYPE_BOOLEAN_INPUT ? as_bool(c->channel) : c->channel;
      return true;
    case ComponentType::Pose:
      if (type != XR_ACTION_TYPE_POSE_INPUT) return false;
      out.kind = c->path == "input/aim/pose" ? SourceKind::AimPose : SourceKind::GripPose;
      return true;
    case ComponentType::Haptic:
      if (type != XR_ACTION_TYPE_VIBRATION_OUTPUT) return false;
      out.kind = SourceKind::Haptic;
      return true;
  }
  return false;
}

std::string user_path_name(std::string_view user) {
  if (user == kLeftHand) return "Left Hand";
  if (user == kRightHand) return "Right Hand";
  if (user == "/user/head") return "Head";
  if (user == "/user/gamepad") return "Gamepad";
  return "Treadmill";
}

std::string component_name(std::string_view path) {
  // "input/a/click" -> "A Button"; "input/squeeze/value" -> "Squeeze"; "input/thumbstick/x" -> "Thumbstick X";
  // "input/trigger/touch" -> "Trigger Touch"; "output/haptic" -> "Haptic".
  const std::size_t first = path.find('/');
  std::string_view rest = path.substr(first + 1);
  const std::size_t slash = rest.find('/');
  std::string_view id = rest.substr(0, slash);
  const std::string_view leaf = slash == std::string_view::npos ? std::string_view() : rest.substr(slash + 1);
  std::string name;
  bool up = true;
  for (char ch : id) {
    if (ch == '_') {
      name += ' ';
      up = true;
    } else {
      name += up && ch >= 'a' && ch <= 'z' ? char(ch - 'a' + 'A') : ch;
      up = false;
    }
  }
  if (id.size() == 1 || id == "menu" || id == "system" || id == "back") name += " Button";
  if (leaf == "touch") name += " Touch";
  if (leaf == "force") name += " Force";
  if (leaf == "x") name += " X";
  if (leaf == "y") name += " Y";
  if (leaf == "pose") name += " Pose";
  return name;
}

}  // namespace wedge::xr_replay

// Suggested bindings, attaching action sets, the current interaction profile, and the bound sources.
// Suggestions are kept per profile (a later one replaces the earlier) until a session attaches; then the
// session's profile is chosen once: oculus/touch_controller if the app suggested bindings for it, else
// khr/simple_controller if it suggested those, else none (XR_NULL_PATH). The chosen profile's suggestions
// are resolved to what the Touch pair reads (profiles.hpp) and copied into the session.
#include <algorithm>

#include "api.hpp"
#include "input.hpp"
#include "registry.hpp"
#include "validate.hpp"

namespace wedge::xr_replay {

namespace {

XrResult suggest(XrInstance instance, const XrInteractionProfileSuggestedBinding* info) {
  Instance* in = find(instance);
  if (in == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (!has_type(info, XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING) || info->countSuggestedBindings == 0 ||
      info->suggestedBindings == nullptr)
    return XR_ERROR_VALIDATION_FAILURE;
  for (uint32_t i = 0; i < info->countSuggestedBindings; ++i) {
    const Action* a = find(info->suggestedBindings[i].action);
    if (a == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (a->set->instance != in) return XR_ERROR_VALIDATION_FAILURE;
  }
  const std::string* profile_path = in->paths.find(info->interactionProfile);
  if (profile_path == nullptr) return XR_ERROR_PATH_INVALID;
  const InteractionProfile* profile = find_profile(*profile_path);
  if (profile == nullptr) return XR_ERROR_PATH_UNSUPPORTED;
  for (uint32_t i = 0; i < info->countSuggestedBindings; ++i) {
    const std::string* binding = in->paths.find(info->suggestedBindings[i].binding);
    if (binding == nullptr) return XR_ERROR_PATH_INVALID;
    BindingTarget target;
    if (!parse_binding(*profile, *binding, target)) return XR_ERROR_PATH_UNSUPPORTED;
    if (*binding == in->config.refused_binding) return XR_ERROR_PATH_UNSUPPORTED;  // (WEDGE_XR_QUIRKS)
  }
  if (in->bindings_frozen) return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
  in->suggestions[info->interactionProfile].assign(info->suggestedBindings,
                                                   info->suggestedBindings + info->countSuggestedBindings);
  return XR_SUCCESS;
}

// The session's copy of one action, its bindings resolved under `profile` (null: none).
BoundAction bind(Instance& in, const Action& a, const InteractionProfile* profile) {
  BoundAction b;
  b.set_id = a.set->id;
  b.type = a.type;
  b.subaction_paths = a.subaction_paths;
  if (profile == nullptr) return b;
  for (const XrActionSuggestedBinding& s : in.suggestions.at(in.paths.lookup(profile->path))) {
    if (id_of(s.action) != a.id) continue;
    BindingTarget target;
    Source source;
    if (!parse_binding(*profile, *in.paths.find(s.binding), target) || !resolve_binding(*profile, target, a.type, source))
      continue;  // no conversion to this action's type, or not a hand: the binding does nothing
    const XrPath user = in.paths.intern(target.user);
    // An action with subaction paths reads only the top-level paths it lists.
    if (!a.subaction_paths.empty() &&
        std::find(a.subaction_paths.begin(), a.subaction_paths.end(), user) == a.subaction_paths.end())
      continue;
    b.sources.push_back(source);
    b.source_subaction.push_back(user);
  }
  return b;
}

XrResult attach(XrSession session, const XrSessionActionSetsAttachInfo* info) {
  Session* s = find(session);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (!has_type(info, XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO) || info->countActionSets == 0 || info->actionSets == nullptr)
    return XR_ERROR_VALIDATION_FAILURE;
  std::vector<ActionSet*> sets;
  for (uint32_t i = 0; i < info->countActionSets; ++i) {
    ActionSet* set = find(info->actionSets[i]);
    if (set == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (set->instance != s->instance) return XR_ERROR_VALIDATION_FAILURE;
    sets.push_back(set);
  }
  if (s->attached) return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
  Instance& in = *s->instance;
  const InteractionProfile* profile = nullptr;
  for (std::string_view p : {kTouchProfile, kSimpleProfile}) {
    const XrPath atom = in.paths.lookup(p);
    if (profile == nullptr && atom != XR_NULL_PATH && in.suggestions.count(atom) > 0) profile = find_profile(p);
  }
  s->attached = true;
  in.bindings_frozen = true;
  s->profile = profile != nullptr ? in.paths.intern(profile->path) : XR_NULL_PATH;
  for (ActionSet* set : sets) {
    set->attached = true;
    s->attached_sets.push_back(set->id);
    for (uint64_t id : set->actions) s->actions.emplace(id, bind(in, *registry().actions.at(id), profile));
  }
  if (profile != nullptr) in.events.push_profile_changed(session);
  return XR_SUCCESS;
}

// The source path's parts, when it is one the current profile has: user path, and the component's path
// below it (or the identifier's, for a 2D input such as input/thumbstick).
bool split_source(const Session& s, const std::string& path, std::string& user, std::string& component) {
  const std::string* profile_path = s.instance->paths.find(s.profile);
  const InteractionProfile* profile = profile_path != nullptr ? find_profile(*profile_path) : nullptr;
  BindingTarget target;
  if (profile == nullptr || !parse_binding(*profile, path, target)) return false;
  user = target.user;
  component = target.component != nullptr ? std::string(target.component->path) : target.identifier;
  return true;
}

XrResult localized_name(XrSession session, const XrInputSourceLocalizedNameGetInfo* info, uint32_t capacity,
                        uint32_t* count, char* buffer) {
  const Session* s = find(session);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  constexpr XrInputSourceLocalizedNameFlags kAll = XR_INPUT_SOURCE_LOCALIZED_NAME_USER_PATH_BIT |
                                                   XR_INPUT_SOURCE_LOCALIZED_NAME_INTERACTION_PROFILE_BIT |
                                                   XR_INPUT_SOURCE_LOCALIZED_NAME_COMPONENT_BIT;
  if (!has_type(info, XR_TYPE_INPUT_SOURCE_LOCALIZED_NAME_GET_INFO) || info->whichComponents == 0 ||
      (info->whichComponents & ~kAll) != 0)
    return XR_ERROR_VALIDATION_FAILURE;
  if (!s->attached) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
  const std::string* path = s->instance->paths.find(info->sourcePath);
  if (path == nullptr) return XR_ERROR_PATH_INVALID;
  std::string user, component;
  if (!split_source(*s, *path, user, component)) return XR_ERROR_PATH_UNSUPPORTED;
  std::string name;
  auto append = [&](const std::string& part) { name += (name.empty() ? "" : " ") + part; };
  if (info->whichComponents & XR_INPUT_SOURCE_LOCALIZED_NAME_USER_PATH_BIT) append(user_path_name(user));
  if (info->whichComponents & XR_INPUT_SOURCE_LOCALIZED_NAME_INTERACTION_PROFILE_BIT)
    append(std::string(find_profile(*s->instance->paths.find(s->profile))->name));
  if (info->whichComponents & XR_INPUT_SOURCE_LOCALIZED_NAME_COMPONENT_BIT) append(component_name(component));
  return two_call_string(capacity, count, buffer, name);
}

}  // namespace

XrResult bound_action(Session& s, const Action& a, BoundAction*& out) {
  if (a.set->instance != s.instance) return XR_ERROR_VALIDATION_FAILURE;
  const auto it = s.actions.find(a.id);
  if (it == s.actions.end()) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
  out = &it->second;
  return XR_SUCCESS;
}

XrResult xrSuggestInteractionProfileBindings(XrInstance instance,
                                             const XrInteractionProfileSuggestedBinding* suggestedBindings) {
  return guarded("xrSuggestInteractionProfileBindings", [&] { return suggest(instance, suggestedBindings); });
}

XrResult xrAttachSessionActionSets(XrSession session, const XrSessionActionSetsAttachInfo* attachInfo) {
  return guarded("xrAttachSessionActionSets", [&] { return attach(session, attachInfo); });
}

XrResult xrGetCurrentInteractionProfile(XrSession session, XrPath topLevelUserPath,
                                        XrInteractionProfileState* interactionProfile) {
  return guarded("xrGetCurrentInteractionProfile", [&]() -> XrResult {
    const Session* s = find(session);
    if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (!has_type(interactionProfile, XR_TYPE_INTERACTION_PROFILE_STATE)) return XR_ERROR_VALIDATION_FAILURE;
    const std::string* user = s->instance->paths.find(topLevelUserPath);
    if (user == nullptr) return XR_ERROR_PATH_INVALID;
    if (!is_top_level_user_path(*user)) return XR_ERROR_PATH_UNSUPPORTED;
    if (!s->attached) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
    interactionProfile->interactionProfile = hand_of(*user) >= 0 ? s->profile : XR_NULL_PATH;
    return XR_SUCCESS;
  });
}

XrResult xrEnumerateBoundSourcesForAction(XrSession session, const XrBoundSourcesForActionEnumerateInfo* enumerateInfo,
                                          uint32_t capacity, uint32_t* count, XrPath* sources) {
  return guarded("xrEnumerateBoundSourcesForAction", [&]() -> XrResult {
    Session* s = find(session);
    if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (!has_type(enumerateInfo, XR_TYPE_BOUND_SOURCES_FOR_ACTION_ENUMERATE_INFO)) return XR_ERROR_VALIDATION_FAILURE;
    const Action* a = find(enumerateInfo->action);
    if (a == nullptr) return XR_ERROR_HANDLE_INVALID;
    BoundAction* b = nullptr;
    if (const XrResult r = bound_action(*s, *a, b); r != XR_SUCCESS) return r;
    std::vector<XrPath> paths;
    for (const Source& src : b->sources) {
      const XrPath p = s->instance->paths.intern(src.path);
      if (std::find(paths.begin(), paths.end(), p) == paths.end()) paths.push_back(p);
    }
    return two_call(capacity, count, sources, paths);
  });
}

XrResult xrGetInputSourceLocalizedName(XrSession session, const XrInputSourceLocalizedNameGetInfo* getInfo,
                                       uint32_t capacity, uint32_t* count, char* buffer) {
  return guarded("xrGetInputSourceLocalizedName",
                 [&] { return localized_name(session, getInfo, capacity, count, buffer); });
}

}  // namespace wedge::xr_replay

// Paths, action sets and actions: xrStringToPath / xrPathToString, creation with the spec's name checks,
// destruction (an attached action keeps working in its session after its handle is gone: bindings.cpp
// copied what the session needs when the sets were attached).
#include <algorithm>
#include <cstring>

#include "api.hpp"
#include "input.hpp"
#include "registry.hpp"
#include "validate.hpp"

namespace wedge::xr_replay {

namespace {

constexpr std::size_t kMaxPaths = 1 << 16;  // atoms per instance (XR_ERROR_PATH_COUNT_EXCEEDED beyond)

// The checks an action set's or an action's names share: the name must be a non-empty path name string,
// the localized name non-empty; neither may repeat among `siblings`.
template <class Siblings, class Get>
XrResult check_names(const char* name, std::size_t name_size, const char* localized, std::size_t localized_size,
                     const Siblings& siblings, Get get) {
  if (name[0] == '\0' || std::memchr(name, '\0', name_size) == nullptr) return XR_ERROR_NAME_INVALID;
  if (!is_path_name(name)) return XR_ERROR_PATH_FORMAT_INVALID;
  if (localized[0] == '\0' || std::memchr(localized, '\0', localized_size) == nullptr)
    return XR_ERROR_LOCALIZED_NAME_INVALID;
  for (uint64_t id : siblings) {
    const auto& o = get(id);
    if (o.name == name) return XR_ERROR_NAME_DUPLICATED;
    if (o.localized_name == localized) return XR_ERROR_LOCALIZED_NAME_DUPLICATED;
  }
  return XR_SUCCESS;
}

bool is_action_type(XrActionType t) {
  return t == XR_ACTION_TYPE_BOOLEAN_INPUT || t == XR_ACTION_TYPE_FLOAT_INPUT || t == XR_ACTION_TYPE_VECTOR2F_INPUT ||
         t == XR_ACTION_TYPE_POSE_INPUT || t == XR_ACTION_TYPE_VIBRATION_OUTPUT;
}

XrResult create_action_set(XrInstance instance, const XrActionSetCreateInfo* info, XrActionSet* out) {
  Instance* in = find(instance);
  if (in == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (!has_type(info, XR_TYPE_ACTION_SET_CREATE_INFO) || out == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  const XrResult r = check_names(info->actionSetName, sizeof(info->actionSetName), info->localizedActionSetName,
                                 sizeof(info->localizedActionSetName), in->action_sets,
                                 [](uint64_t id) -> const ActionSet& { return *registry().action_sets.at(id); });
  if (r != XR_SUCCESS) return r;
  auto set = std::make_unique<ActionSet>();
  set->instance = in;
  set->name = info->actionSetName;
  set->localized_name = info->localizedActionSetName;
  set->priority = info->priority;
  *out = handle_of<XrActionSet>(add(std::move(set))->id);
  return XR_SUCCESS;
}

XrResult create_action(XrActionSet actionSet, const XrActionCreateInfo* info, XrAction* out) {
  ActionSet* set = find(actionSet);
  if (set == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (!has_type(info, XR_TYPE_ACTION_CREATE_INFO) || out == nullptr || !is_action_type(info->actionType) ||
      (info->countSubactionPaths > 0 && info->subactionPaths == nullptr))
    return XR_ERROR_VALIDATION_FAILURE;
  if (set->attached) return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
  const XrResult r = check_names(info->actionName, sizeof(info->actionName), info->localizedActionName,
                                 sizeof(info->localizedActionName), set->actions,
                                 [](uint64_t id) -> const Action& { return *registry().actions.at(id); });
  if (r != XR_SUCCESS) return r;
  std::vector<XrPath> paths;
  for (uint32_t i = 0; i < info->countSubactionPaths; ++i) {
    const XrPath p = info->subactionPaths[i];
    const std::string* s = set->instance->paths.find(p);
    if (s == nullptr) return XR_ERROR_PATH_INVALID;
    if (!is_top_level_user_path(*s) || std::find(paths.begin(), paths.end(), p) != paths.end())
      return XR_ERROR_PATH_UNSUPPORTED;
    paths.push_back(p);
  }
  auto a = std::make_unique<Action>();
  a->set = set;
  a->name = info->actionName;
  a->localized_name = info->localizedActionName;
  a->type = info->actionType;
  a->subaction_paths = std::move(paths);
  *out = handle_of<XrAction>(add(std::move(a))->id);
  return XR_SUCCESS;
}

}  // namespace

XrResult check_subaction_path(const Instance& in, const std::vector<XrPath>& subaction_paths, XrPath p) {
  if (p == XR_NULL_PATH) return XR_SUCCESS;
  if (!in.paths.is_valid(p)) return XR_ERROR_PATH_INVALID;
  return std::find(subaction_paths.begin(), subaction_paths.end(), p) != subaction_paths.end()
             ? XR_SUCCESS
             : XR_ERROR_PATH_UNSUPPORTED;
}

XrResult xrStringToPath(XrInstance instance, const char* pathString, XrPath* path) {
  return guarded("xrStringToPath", [&]() -> XrResult {
    Instance* in = find(instance);
    if (in == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (pathString == nullptr || path == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    if (!is_well_formed_path(pathString)) return XR_ERROR_PATH_FORMAT_INVALID;
    if (in->paths.lookup(pathString) == XR_NULL_PATH && in->paths.find(XrPath(kMaxPaths)) != nullptr)
      return XR_ERROR_PATH_COUNT_EXCEEDED;
    *path = in->paths.intern(pathString);
    return XR_SUCCESS;
  });
}

XrResult xrPathToString(XrInstance instance, XrPath path, uint32_t capacity, uint32_t* count, char* buffer) {
  return guarded("xrPathToString", [&]() -> XrResult {
    const Instance* in = find(instance);
    if (in == nullptr) return XR_ERROR_HANDLE_INVALID;
    const std::string* s = in->paths.find(path);
    if (s == nullptr) return XR_ERROR_PATH_INVALID;
    return two_call_string(capacity, count, buffer, *s);
  });
}

XrResult xrCreateActionSet(XrInstance instance, const XrActionSetCreateInfo* createInfo, XrActionSet* actionSet) {
  return guarded("xrCreateActionSet", [&] { return create_action_set(instance, createInfo, actionSet); });
}

XrResult xrDestroyActionSet(XrActionSet actionSet) {
  return guarded("xrDestroyActionSet", [&]() -> XrResult {
    ActionSet* set = find(actionSet);
    if (set == nullptr) return XR_ERROR_HANDLE_INVALID;
    destroy(set);
    return XR_SUCCESS;
  });
}

XrResult xrCreateAction(XrActionSet actionSet, const XrActionCreateInfo* createInfo, XrAction* action) {
  return guarded("xrCreateAction", [&] { return create_action(actionSet, createInfo, action); });
}

XrResult xrDestroyAction(XrAction action) {
  return guarded("xrDestroyAction", [&]() -> XrResult {
    Action* a = find(action);
    if (a == nullptr) return XR_ERROR_HANDLE_INVALID;
    destroy(a);
    return XR_SUCCESS;
  });
}

}  // namespace wedge::xr_replay

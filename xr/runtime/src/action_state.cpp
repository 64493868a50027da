// xrSyncActions and the action state getters (docs/xr-runtime.md, "Actions").
//
// A sync samples the recording at the session's frame time: the latest predicted display time xrWaitFrame
// handed out (kEpoch before the first). States only change at a sync. For each action and each filter (no
// subaction path, or one of the action's) the sources bound under the current profile are combined as the
// spec says: booleans by OR, floats and 2D inputs by the largest magnitude (the first bound on a tie).
// lastChangeTime is the XrTime of the recording sample at which the combined value became what it is: the
// deciding source's change time (for an OR that holds, the earliest change among the sources that are on;
// for one that is off, the latest change among all).
#include <algorithm>
#include <cmath>

#include "api.hpp"
#include "input.hpp"
#include "registry.hpp"
#include "session_state.hpp"
#include "validate.hpp"

namespace wedge::xr_replay {

namespace {

// Active sets of a sync: set id -> the subaction paths it is active for (XR_NULL_PATH: all).
using ActiveSets = std::map<uint64_t, std::vector<XrPath>>;

bool passes(const std::vector<XrPath>& set_filters, XrPath user) {
  return std::any_of(set_filters.begin(), set_filters.end(), [&](XrPath f) { return f == XR_NULL_PATH || f == user; });
}

// The state of `b` for `filter` at time t, from the sources the filter and the active sets let through.
ActionState evaluate(const Playback& playback, const BoundAction& b, XrPath filter, const std::vector<XrPath>& set_filters,
                     XrTime t) {
  ActionState out;
  bool any = false, on = false;
  XrTime earliest_on = 0, latest = 0;
  double best = -1.0;
  for (std::size_t i = 0; i < b.sources.size(); ++i) {
    const Source& src = b.sources[i];
    if ((filter != XR_NULL_PATH && b.source_subaction[i] != filter) || !passes(set_filters, b.source_subaction[i]))
      continue;
    any = true;
    if (src.kind != SourceKind::Value) continue;  // poses, haptics and 2D inputs (always 0, 0) carry no value
    const ChannelValue v = playback.channel(src.hand, src.channel, t);
    if (b.type == XR_ACTION_TYPE_BOOLEAN_INPUT) {
      latest = std::max(latest, v.changed_at);
      if (v.value != 0.0) earliest_on = on ? std::min(earliest_on, v.changed_at) : v.changed_at;
      on = on || v.value != 0.0;
    } else if (std::abs(v.value) > best) {
      best = std::abs(v.value);
      out.value = v.value;
      out.last_change = v.changed_at;
    }
  }
  if (!any) return out;
  out.active = true;
  if (b.type == XR_ACTION_TYPE_BOOLEAN_INPUT) {
    out.value = on ? 1.0 : 0.0;
    out.last_change = on ? earliest_on : latest;
  } else if (best < 0.0) {
    out.last_change = kEpoch;  // a 2D input (or a float bound only to one): at rest since the start
  }
  return out;
}

XrResult sync(XrSession session, const XrActionsSyncInfo* info) {
  Session* s = find(session);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (!has_type(info, XR_TYPE_ACTIONS_SYNC_INFO) || (info->countActiveActionSets > 0 && info->activeActionSets == nullptr))
    return XR_ERROR_VALIDATION_FAILURE;
  ActiveSets active;
  for (uint32_t i = 0; i < info->countActiveActionSets; ++i) {
    const XrActiveActionSet& a = info->activeActionSets[i];
    const ActionSet* set = find(a.actionSet);
    if (set == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (std::find(s->attached_sets.begin(), s->attached_sets.end(), set->id) == s->attached_sets.end())
      return XR_ERROR_ACTIONSET_NOT_ATTACHED;
    if (a.subactionPath != XR_NULL_PATH) {
      const std::string* p = s->instance->paths.find(a.subactionPath);
      if (p == nullptr) return XR_ERROR_PATH_INVALID;
      if (!is_top_level_user_path(*p)) return XR_ERROR_PATH_UNSUPPORTED;
    }
    active[set->id].push_back(a.subactionPath);
  }
  const bool focused = is_focused(*s);
  s->input_focused = focused;
  for (auto& [id, b] : s->actions) {
    const auto set = active.find(b.set_id);
    std::vector<XrPath> filters{XR_NULL_PATH};
    filters.insert(filters.end(), b.subaction_paths.begin(), b.subaction_paths.end());
    for (XrPath f : filters) {
      const ActionState before = b.states[f];
      ActionState now;  // inactive unless focused and its set is active
      if (focused && set != active.end()) now = evaluate(s->instance->playback, b, f, set->second, s->now);
      now.changed = before.active && now.active && (now.value != before.value || now.y != before.y);
      b.states[f] = now;
    }
  }
  return focused ? XR_SUCCESS : XR_SESSION_NOT_FOCUSED;
}

// The checks every getter shares (out_ok: the app's output struct has the right type); on success `state`
// is the action's last synced state for the filter.
XrResult get_state(XrSession session, const XrActionStateGetInfo* info, bool out_ok, XrActionType type,
                   const ActionState*& state) {
  static const ActionState kInactive;
  Session* s = find(session);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (!out_ok || !has_type(info, XR_TYPE_ACTION_STATE_GET_INFO)) return XR_ERROR_VALIDATION_FAILURE;
  const Action* a = find(info->action);
  if (a == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (a->type != type) return XR_ERROR_ACTION_TYPE_MISMATCH;
  BoundAction* b = nullptr;
  if (const XrResult r = bound_action(*s, *a, b); r != XR_SUCCESS) return r;
  if (const XrResult r = check_subaction_path(*s->instance, b->subaction_paths, info->subactionPath); r != XR_SUCCESS)
    return r;
  const auto it = b->states.find(info->subactionPath);
  state = it != b->states.end() ? &it->second : &kInactive;
  return XR_SUCCESS;
}

}  // namespace

const Source* active_pose_source(const Session& s, uint64_t action, XrPath filter) {
  const auto it = s.actions.find(action);
  if (it == s.actions.end()) return nullptr;
  const BoundAction& b = it->second;
  const auto state = b.states.find(filter);
  if (state == b.states.end() || !state->second.active) return nullptr;
  for (std::size_t i = 0; i < b.sources.size(); ++i)
    if ((filter == XR_NULL_PATH || b.source_subaction[i] == filter) &&
        (b.sources[i].kind == SourceKind::GripPose || b.sources[i].kind == SourceKind::AimPose))
      return &b.sources[i];
  return nullptr;
}

XrResult xrSyncActions(XrSession session, const XrActionsSyncInfo* syncInfo) {
  return guarded("xrSyncActions", [&] { return sync(session, syncInfo); });
}

XrResult xrGetActionStateBoolean(XrSession session, const XrActionStateGetInfo* getInfo, XrActionStateBoolean* state) {
  return guarded("xrGetActionStateBoolean", [&]() -> XrResult {
    const ActionState* a = nullptr;
    const bool out_ok = has_type(state, XR_TYPE_ACTION_STATE_BOOLEAN);
    if (const XrResult r = get_state(session, getInfo, out_ok, XR_ACTION_TYPE_BOOLEAN_INPUT, a); r != XR_SUCCESS) return r;
    state->currentState = a->value != 0.0 ? XR_TRUE : XR_FALSE;
    state->changedSinceLastSync = a->changed ? XR_TRUE : XR_FALSE;
    state->lastChangeTime = a->active ? a->last_change : 0;
    state->isActive = a->active ? XR_TRUE : XR_FALSE;
    return XR_SUCCESS;
  });
}

XrResult xrGetActionStateFloat(XrSession session, const XrActionStateGetInfo* getInfo, XrActionStateFloat* state) {
  return guarded("xrGetActionStateFloat", [&]() -> XrResult {
    const ActionState* a = nullptr;
    const bool out_ok = has_type(state, XR_TYPE_ACTION_STATE_FLOAT);
    if (const XrResult r = get_state(session, getInfo, out_ok, XR_ACTION_TYPE_FLOAT_INPUT, a); r != XR_SUCCESS) return r;
    state->currentState = float(a->value);
    state->changedSinceLastSync = a->changed ? XR_TRUE : XR_FALSE;
    state->lastChangeTime = a->active ? a->last_change : 0;
    state->isActive = a->active ? XR_TRUE : XR_FALSE;
    return XR_SUCCESS;
  });
}

XrResult xrGetActionStateVector2f(XrSession session, const XrActionStateGetInfo* getInfo, XrActionStateVector2f* state) {
  return guarded("xrGetActionStateVector2f", [&]() -> XrResult {
    const ActionState* a = nullptr;
    const bool out_ok = has_type(state, XR_TYPE_ACTION_STATE_VECTOR2F);
    if (const XrResult r = get_state(session, getInfo, out_ok, XR_ACTION_TYPE_VECTOR2F_INPUT, a); r != XR_SUCCESS) return r;
    state->currentState = {float(a->value), float(a->y)};
    state->changedSinceLastSync = a->changed ? XR_TRUE : XR_FALSE;
    state->lastChangeTime = a->active ? a->last_change : 0;
    state->isActive = a->active ? XR_TRUE : XR_FALSE;
    return XR_SUCCESS;
  });
}

XrResult xrGetActionStatePose(XrSession session, const XrActionStateGetInfo* getInfo, XrActionStatePose* state) {
  return guarded("xrGetActionStatePose", [&]() -> XrResult {
    const ActionState* a = nullptr;
    const bool out_ok = has_type(state, XR_TYPE_ACTION_STATE_POSE);
    if (const XrResult r = get_state(session, getInfo, out_ok, XR_ACTION_TYPE_POSE_INPUT, a); r != XR_SUCCESS) return r;
    state->isActive = a->active ? XR_TRUE : XR_FALSE;
    return XR_SUCCESS;
  });
}

}  // namespace wedge::xr_replay

// xrApplyHapticFeedback / xrStopHapticFeedback, recorded in the haptics log (haptics.hpp has its format).
// A call on a session that is not focused is ignored with XR_SESSION_NOT_FOCUSED, as the spec says; one on
// an action that the last xrSyncActions left inactive (its set not synced, or no /output/haptic bound for
// the subaction path) reaches no hand and writes nothing.
#include "haptics.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "api.hpp"
#include "decimal.hpp"
#include "input.hpp"
#include "registry.hpp"
#include "session_state.hpp"
#include "validate.hpp"

namespace wedge::xr_replay {

namespace {

using nlohmann::ordered_json;

ordered_json line_start(const char* call, XrTime now, std::string_view hand) {
  return {{"call", call}, {"time_ns", now}, {"t", xr_time_to_recording_seconds(now)}, {"hand", hand}};
}

// The checks both calls share; on success `hands` lists the user paths of the bound haptic outputs the
// call reaches (empty when the action is inactive), and the result is XR_SUCCESS or XR_SESSION_NOT_FOCUSED.
XrResult haptic_targets(XrSession session, const XrHapticActionInfo* info, bool feedback_ok, Session*& s,
                        std::vector<std::string>& hands) {
  s = find(session);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (!has_type(info, XR_TYPE_HAPTIC_ACTION_INFO) || !feedback_ok) return XR_ERROR_VALIDATION_FAILURE;
  const Action* a = find(info->action);
  if (a == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (a->type != XR_ACTION_TYPE_VIBRATION_OUTPUT) return XR_ERROR_ACTION_TYPE_MISMATCH;
  BoundAction* b = nullptr;
  if (const XrResult r = bound_action(*s, *a, b); r != XR_SUCCESS) return r;
  if (const XrResult r = check_subaction_path(*s->instance, b->subaction_paths, info->subactionPath); r != XR_SUCCESS)
    return r;
  if (!is_focused(*s)) return XR_SESSION_NOT_FOCUSED;
  const auto state = b->states.find(info->subactionPath);
  if (state == b->states.end() || !state->second.active) return XR_SUCCESS;
  for (std::size_t i = 0; i < b->sources.size(); ++i) {
    if (b->sources[i].kind != SourceKind::Haptic) continue;
    if (info->subactionPath != XR_NULL_PATH && b->source_subaction[i] != info->subactionPath) continue;
    const std::string& user = *s->instance->paths.find(b->source_subaction[i]);
    if (std::find(hands.begin(), hands.end(), user) == hands.end()) hands.push_back(user);
  }
  return XR_SUCCESS;
}

}  // namespace

void HapticsLog::apply(XrTime now, std::string_view hand, const XrHapticVibration& v) {
  if (path_.empty()) return;
  ordered_json line = line_start("apply", now, hand);
  line["amplitude"] = float_as_decimal(v.amplitude);
  line["duration_ns"] = v.duration;
  line["frequency"] = float_as_decimal(v.frequency);
  write(line.dump());
}

void HapticsLog::stop(XrTime now, std::string_view hand) {
  if (path_.empty()) return;
  write(line_start("stop", now, hand).dump());
}

void HapticsLog::write(const std::string& line) {
  if (!file_) {
    file_.reset(std::fopen(path_.c_str(), "a"));
    if (!file_) {
      report("WEDGE_XR_HAPTICS_LOG=" + path_ + ": cannot open for appending; haptic calls are not logged");
      path_.clear();
      return;
    }
  }
  std::fprintf(file_.get(), "%s\n", line.c_str());
  std::fflush(file_.get());
}

XrResult xrApplyHapticFeedback(XrSession session, const XrHapticActionInfo* hapticActionInfo,
                               const XrHapticBaseHeader* hapticFeedback) {
  return guarded("xrApplyHapticFeedback", [&]() -> XrResult {
    Session* s = nullptr;
    std::vector<std::string> hands;
    const bool feedback_ok = has_type(hapticFeedback, XR_TYPE_HAPTIC_VIBRATION);
    const XrResult r = haptic_targets(session, hapticActionInfo, feedback_ok, s, hands);
    if (r != XR_SUCCESS) return r;
    const auto& v = *reinterpret_cast<const XrHapticVibration*>(hapticFeedback);
    for (const std::string& hand : hands) s->instance->haptics.apply(s->now, hand, v);
    return XR_SUCCESS;
  });
}

XrResult xrStopHapticFeedback(XrSession session, const XrHapticActionInfo* hapticActionInfo) {
  return guarded("xrStopHapticFeedback", [&]() -> XrResult {
    Session* s = nullptr;
    std::vector<std::string> hands;
    const XrResult r = haptic_targets(session, hapticActionInfo, true, s, hands);
    if (r != XR_SUCCESS) return r;
    for (const std::string& hand : hands) s->instance->haptics.stop(s->now, hand);
    return XR_SUCCESS;
  });
}

}  // namespace wedge::xr_replay

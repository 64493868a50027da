// What the input files (actions.cpp, bindings.cpp, action_state.cpp, haptics.cpp, spaces.cpp) share.
#pragma once

#include <vector>

#include "objects.hpp"

namespace wedge::xr_replay {

// A subaction path argument against an action's list: XR_NULL_PATH is always fine; an atom never handed
// out is XR_ERROR_PATH_INVALID; a path not in the action's list is XR_ERROR_PATH_UNSUPPORTED.
XrResult check_subaction_path(const Instance& in, const std::vector<XrPath>& subaction_paths, XrPath p);

// The session's view of an action: XR_ERROR_ACTIONSET_NOT_ATTACHED when its set is not attached to this
// session (or the action belongs to another instance: XR_ERROR_VALIDATION_FAILURE).
XrResult bound_action(Session& s, const Action& a, BoundAction*& out);

// The pose source an action space reads: the action's first bound pose for the filter, when the last
// xrSyncActions left the action active for it; else null (the space is then not located).
const Source* active_pose_source(const Session& s, uint64_t action, XrPath filter);

}  // namespace wedge::xr_replay

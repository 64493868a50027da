// Reference spaces (VIEW, LOCAL, STAGE), action spaces, xrLocateSpace and xrLocateViews.
#include "spaces.hpp"

#include <cmath>

#include "api.hpp"
#include "input.hpp"
#include "registry.hpp"
#include "system.hpp"
#include "validate.hpp"

namespace wedge::xr_replay {

namespace {

constexpr double kHalfIpd = 0.0315;  // m: each eye sits this far along the head's x axis
constexpr double kPi = 3.14159265358979323846;
// Symmetric field of view of each eye: 45 degrees left and right, 50 up and down.
constexpr float kFovHorizontal = float(45.0 * kPi / 180.0), kFovVertical = float(50.0 * kPi / 180.0);

// XR_SUCCESS for the three reference spaces of the core API (the runtime has all of them); any other value
// (those of extensions included: the runtime offers none that defines one) is XR_ERROR_VALIDATION_FAILURE.
XrResult check_reference_space(XrReferenceSpaceType t) {
  const bool core = t == XR_REFERENCE_SPACE_TYPE_VIEW || t == XR_REFERENCE_SPACE_TYPE_LOCAL ||
                    t == XR_REFERENCE_SPACE_TYPE_STAGE;
  return core ? XR_SUCCESS : XR_ERROR_VALIDATION_FAILURE;
}

// A moving frame's pose and velocities, then an offset pose rigidly attached to it.
Located attach(const TrackedPose& body, const Pose& offset) {
  Located out;
  out.valid = body.tracked;
  out.pose = compose(body.pose, offset);
  const Eigen::Vector3d arm = body.pose.orientation * offset.position;
  out.linear_velocity = body.linear_velocity + body.angular_velocity.cross(arm);
  out.angular_velocity = body.angular_velocity;
  return out;
}

// `space` relative to `base`: pose and velocities expressed in base's frame.
Located relative(const Located& space, const Located& base) {
  Located out;
  out.valid = space.valid && base.valid;
  if (!out.valid) return out;
  out.pose = compose(inverse(base.pose), space.pose);
  const Eigen::Quaterniond to_base = base.pose.orientation.conjugate();
  const Eigen::Vector3d arm = space.pose.position - base.pose.position;
  out.linear_velocity = to_base * (space.linear_velocity - base.linear_velocity - base.angular_velocity.cross(arm));
  out.angular_velocity = to_base * (space.angular_velocity - base.angular_velocity);
  return out;
}

XrVector3f to_xr(const Eigen::Vector3d& v) { return {float(v.x()), float(v.y()), float(v.z())}; }

XrResult create_action_space(XrSession session, const XrActionSpaceCreateInfo* info, XrSpace* out) {
  Session* s = find(session);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (!has_type(info, XR_TYPE_ACTION_SPACE_CREATE_INFO) || out == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  const Action* a = find(info->action);
  if (a == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (a->set->instance != s->instance) return XR_ERROR_VALIDATION_FAILURE;
  if (a->type != XR_ACTION_TYPE_POSE_INPUT) return XR_ERROR_ACTION_TYPE_MISMATCH;
  if (const XrResult r = check_subaction_path(*s->instance, a->subaction_paths, info->subactionPath); r != XR_SUCCESS)
    return r;
  if (!is_valid_pose(info->poseInActionSpace)) return XR_ERROR_POSE_INVALID;
  auto space = std::make_unique<Space>();
  space->session = s;
  space->is_action = true;
  space->action = a->id;
  space->subaction = info->subactionPath;
  space->offset = from_xr(info->poseInActionSpace);
  *out = handle_of<XrSpace>(add(std::move(space))->id);
  return XR_SUCCESS;
}

XrResult locate_space(XrSpace space, XrSpace baseSpace, XrTime time, XrSpaceLocation* location) {
  const Space* s = find(space);
  const Space* b = find(baseSpace);
  if (s == nullptr || b == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (!has_type(location, XR_TYPE_SPACE_LOCATION)) return XR_ERROR_VALIDATION_FAILURE;
  if (s->session != b->session) return XR_ERROR_VALIDATION_FAILURE;
  if (time <= 0) return XR_ERROR_TIME_INVALID;
  const Located r = relative(locate(*s, time), locate(*b, time));
  auto* velocity = const_cast<XrSpaceVelocity*>(
      reinterpret_cast<const XrSpaceVelocity*>(find_in_chain(location->next, XR_TYPE_SPACE_VELOCITY)));
  location->locationFlags = 0;
  location->pose = to_xr(Pose{});
  if (velocity != nullptr) velocity->velocityFlags = 0;
  if (!r.valid) return XR_SUCCESS;
  location->locationFlags = XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT |
                            XR_SPACE_LOCATION_POSITION_TRACKED_BIT | XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT;
  location->pose = to_xr(r.pose);
  if (velocity != nullptr) {
    velocity->velocityFlags = XR_SPACE_VELOCITY_LINEAR_VALID_BIT | XR_SPACE_VELOCITY_ANGULAR_VALID_BIT;
    velocity->linearVelocity = to_xr(r.linear_velocity);
    velocity->angularVelocity = to_xr(r.angular_velocity);
  }
  return XR_SUCCESS;
}

XrResult locate_views(XrSession session, const XrViewLocateInfo* info, XrViewState* state, uint32_t capacity,
                      uint32_t* count, XrView* views) {
  Session* s = find(session);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (!has_type(info, XR_TYPE_VIEW_LOCATE_INFO) || !has_type(state, XR_TYPE_VIEW_STATE) || count == nullptr)
    return XR_ERROR_VALIDATION_FAILURE;
  if (const XrResult r = check_view_configuration(info->viewConfigurationType); r != XR_SUCCESS) return r;
  const Space* base = find(info->space);
  if (base == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (base->session != s) return XR_ERROR_VALIDATION_FAILURE;
  if (info->displayTime <= 0) return XR_ERROR_TIME_INVALID;
  const Located head = relative(attach(s->instance->playback.head(info->displayTime), Pose{}),
                                locate(*base, info->displayTime));
  state->viewStateFlags = head.valid ? XR_VIEW_STATE_POSITION_VALID_BIT | XR_VIEW_STATE_ORIENTATION_VALID_BIT |
                                           XR_VIEW_STATE_POSITION_TRACKED_BIT | XR_VIEW_STATE_ORIENTATION_TRACKED_BIT
                                     : 0;
  return two_call_structs(capacity, count, views, kViewCount, XR_TYPE_VIEW, [&](uint32_t i, XrView& v) {
    Pose eye;
    eye.position.x() = i == 0 ? -kHalfIpd : kHalfIpd;  // view 0 is the left eye
    v.pose = to_xr(head.valid ? compose(head.pose, eye) : Pose{});
    v.fov = {-kFovHorizontal, kFovHorizontal, kFovVertical, -kFovVertical};
  });
}

}  // namespace

Pose aim_in_grip() {
  return {Eigen::Vector3d(0.0, 0.0, -0.05), Eigen::Quaterniond(Eigen::AngleAxisd(-kPi / 6.0, Eigen::Vector3d::UnitX()))};
}

Located locate(const Space& space, XrTime t) {
  const Playback& playback = space.session->instance->playback;
  if (!space.is_action) {
    if (space.reference == XR_REFERENCE_SPACE_TYPE_VIEW) return attach(playback.head(t), space.offset);
    TrackedPose still;  // LOCAL is the tracking space itself; STAGE's origin is on the floor below it
    still.tracked = true;
    if (space.reference == XR_REFERENCE_SPACE_TYPE_STAGE) still.pose.position.y() = -kStageDepth;
    return attach(still, space.offset);
  }
  const Source* source = active_pose_source(*space.session, space.action, space.subaction);
  if (source == nullptr) return {};
  const TrackedPose grip = playback.grip(source->hand, t);
  if (source->kind == SourceKind::GripPose) return attach(grip, space.offset);
  return attach(grip, compose(aim_in_grip(), space.offset));
}

const char* space_type_name(const Space& space) {
  if (space.is_action) return "ACTION";
  switch (space.reference) {
    case XR_REFERENCE_SPACE_TYPE_VIEW: return "VIEW";
    case XR_REFERENCE_SPACE_TYPE_STAGE: return "STAGE";
    default: return "LOCAL";
  }
}

XrResult xrEnumerateReferenceSpaces(XrSession session, uint32_t capacity, uint32_t* count, XrReferenceSpaceType* spaces) {
  return guarded("xrEnumerateReferenceSpaces", [&]() -> XrResult {
    if (find(session) == nullptr) return XR_ERROR_HANDLE_INVALID;
    return two_call(capacity, count, spaces,
                    std::vector<XrReferenceSpaceType>{XR_REFERENCE_SPACE_TYPE_VIEW, XR_REFERENCE_SPACE_TYPE_LOCAL,
                                                      XR_REFERENCE_SPACE_TYPE_STAGE});
  });
}

XrResult xrCreateReferenceSpace(XrSession session, const XrReferenceSpaceCreateInfo* createInfo, XrSpace* space) {
  return guarded("xrCreateReferenceSpace", [&]() -> XrResult {
    Session* s = find(session);
    if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (!has_type(createInfo, XR_TYPE_REFERENCE_SPACE_CREATE_INFO) || space == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    if (const XrResult r = check_reference_space(createInfo->referenceSpaceType); r != XR_SUCCESS) return r;
    if (!is_valid_pose(createInfo->poseInReferenceSpace)) return XR_ERROR_POSE_INVALID;
    auto o = std::make_unique<Space>();
    o->session = s;
    o->reference = createInfo->referenceSpaceType;
    o->offset = from_xr(createInfo->poseInReferenceSpace);
    *space = handle_of<XrSpace>(add(std::move(o))->id);
    return XR_SUCCESS;
  });
}

XrResult xrGetReferenceSpaceBoundsRect(XrSession session, XrReferenceSpaceType type, XrExtent2Df* bounds) {
  return guarded("xrGetReferenceSpaceBoundsRect", [&]() -> XrResult {
    if (find(session) == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (bounds == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    if (const XrResult r = check_reference_space(type); r != XR_SUCCESS) return r;
    if (type != XR_REFERENCE_SPACE_TYPE_STAGE) {
      *bounds = {0.0f, 0.0f};
      return XR_SPACE_BOUNDS_UNAVAILABLE;
    }
    *bounds = {2.0f, 2.0f};  // a 2 m x 2 m play area centred on the STAGE origin
    return XR_SUCCESS;
  });
}

XrResult xrCreateActionSpace(XrSession session, const XrActionSpaceCreateInfo* createInfo, XrSpace* space) {
  return guarded("xrCreateActionSpace", [&] { return create_action_space(session, createInfo, space); });
}

XrResult xrLocateSpace(XrSpace space, XrSpace baseSpace, XrTime time, XrSpaceLocation* location) {
  return guarded("xrLocateSpace", [&] { return locate_space(space, baseSpace, time, location); });
}

XrResult xrDestroySpace(XrSpace space) {
  return guarded("xrDestroySpace", [&]() -> XrResult {
    Space* s = find(space);
    if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
    destroy(s);
    return XR_SUCCESS;
  });
}

XrResult xrLocateViews(XrSession session, const XrViewLocateInfo* viewLocateInfo, XrViewState* viewState,
                       uint32_t capacity, uint32_t* count, XrView* views) {
  return guarded("xrLocateViews", [&] { return locate_views(session, viewLocateInfo, viewState, capacity, count, views); });
}

}  // namespace wedge::xr_replay

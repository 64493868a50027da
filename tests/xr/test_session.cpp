// Sessions: the state machine against the recording's end, the deterministic frame clock, headless
// refusals, handle and struct validation, reference spaces and views.
#include <cmath>
#include <cstring>
#include <memory>

#include "xr_test_support.hpp"

using namespace xrtest;
using wedge::recordings::Hand;

namespace {

constexpr double kPi = 3.14159265358979323846;

const XrEventDataSessionStateChanged& as_state(const XrEventDataBuffer& e) {
  REQUIRE(e.type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED);
  return reinterpret_cast<const XrEventDataSessionStateChanged&>(e);
}

XrSessionBeginInfo stereo_begin() {
  XrSessionBeginInfo b = xr_struct<XrSessionBeginInfo>(XR_TYPE_SESSION_BEGIN_INFO);
  b.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
  return b;
}

}  // namespace

TEST_CASE("xr runtime: a headless session runs IDLE to FOCUSED, stops when the recording ends, then exits") {
  wedge::recordings::Recording r;
  r.source = "script";
  for (double t : {0.0, 0.5, 1.0}) r.hands.push_back(hand(t, Hand::Right, {0.1, 1.0, -0.3}));
  runtime_env({{"WEDGE_XR_REPLAY", write_test_recording("state_machine.jsonl", r)}});
  Instance instance;
  HeadlessSession session(instance, false);
  XrSession s = session.get();

  std::vector<XrEventDataBuffer> events = instance.poll_events();
  REQUIRE(states_of(events) == std::vector<XrSessionState>{XR_SESSION_STATE_IDLE, XR_SESSION_STATE_READY});
  for (const auto& e : events) {
    CHECK(as_state(e).session == s);
    CHECK(as_state(e).time == kEpoch);
  }
  XrFrameState frame = xr_struct<XrFrameState>(XR_TYPE_FRAME_STATE);
  CHECK(xrWaitFrame(s, nullptr, &frame) == XR_ERROR_SESSION_NOT_RUNNING);
  CHECK(xrEndSession(s) == XR_ERROR_SESSION_NOT_RUNNING);
  CHECK(xrRequestExitSession(s) == XR_ERROR_SESSION_NOT_RUNNING);
  XrSessionBeginInfo mono = xr_struct<XrSessionBeginInfo>(XR_TYPE_SESSION_BEGIN_INFO);
  mono.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_MONO;
  CHECK(xrBeginSession(s, &mono) == XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED);
  const XrSessionBeginInfo begin = stereo_begin();
  REQUIRE(xrBeginSession(s, &begin) == XR_SUCCESS);
  CHECK(xrBeginSession(s, &begin) == XR_ERROR_SESSION_RUNNING);
  CHECK(states_of(instance.poll_events()) == std::vector<XrSessionState>{XR_SESSION_STATE_SYNCHRONIZED,
                                                                          XR_SESSION_STATE_VISIBLE,
                                                                          XR_SESSION_STATE_FOCUSED});
  CHECK(xrEndSession(s) == XR_ERROR_SESSION_NOT_STOPPING);

  // A headless session has no frames to show.
  XrFrameEndInfo end = xr_struct<XrFrameEndInfo>(XR_TYPE_FRAME_END_INFO);
  end.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
  CHECK(xrBeginFrame(s, nullptr) == XR_ERROR_VALIDATION_FAILURE);
  CHECK(xrEndFrame(s, &end) == XR_ERROR_VALIDATION_FAILURE);
  uint32_t formats = 99;
  CHECK(xrEnumerateSwapchainFormats(s, 0, &formats, nullptr) == XR_SUCCESS);
  CHECK(formats == 0);

  // The last sample is at 1 s: frame 90 is displayed exactly then (not past it), frame 91 is past it.
  for (uint64_t n = 0; n <= 90; ++n) {
    frame = session.wait_frame();
    REQUIRE(frame.predictedDisplayTime == frame_time(n));
    REQUIRE(frame.predictedDisplayPeriod == 11'111'111);
    REQUIRE(frame.shouldRender == XR_FALSE);
    REQUIRE(instance.poll_events().empty());
  }
  frame = session.wait_frame();
  CHECK(frame.predictedDisplayTime == frame_time(91));
  events = instance.poll_events();
  CHECK(states_of(events) == std::vector<XrSessionState>{XR_SESSION_STATE_VISIBLE, XR_SESSION_STATE_SYNCHRONIZED,
                                                          XR_SESSION_STATE_STOPPING});
  for (const auto& e : events) CHECK(as_state(e).time == frame_time(91));
  REQUIRE(xrEndSession(s) == XR_SUCCESS);
  CHECK(states_of(instance.poll_events()) ==
        std::vector<XrSessionState>{XR_SESSION_STATE_IDLE, XR_SESSION_STATE_EXITING});
  CHECK(xrWaitFrame(s, nullptr, &frame) == XR_ERROR_SESSION_NOT_RUNNING);
}

TEST_CASE("xr runtime: predicted display times are kEpoch + round(n * 1e9 / 90), exactly, for many frames") {
  runtime_env();
  Instance instance;
  HeadlessSession session(instance);
  for (uint64_t n = 0; n < 20000; ++n) REQUIRE(session.wait_frame().predictedDisplayTime == frame_time(n));
}

TEST_CASE("xr runtime: without a recording a session never stops by itself, xrRequestExitSession stops it") {
  runtime_env();
  Instance instance;
  HeadlessSession session(instance);
  instance.poll_events();
  for (int n = 0; n < 2000; ++n) session.wait_frame();
  CHECK(instance.poll_events().empty());
  REQUIRE(xrRequestExitSession(session.get()) == XR_SUCCESS);
  CHECK(states_of(instance.poll_events()) == std::vector<XrSessionState>{XR_SESSION_STATE_VISIBLE,
                                                                          XR_SESSION_STATE_SYNCHRONIZED,
                                                                          XR_SESSION_STATE_STOPPING});
  REQUIRE(xrEndSession(session.get()) == XR_SUCCESS);
  CHECK(states_of(instance.poll_events()) ==
        std::vector<XrSessionState>{XR_SESSION_STATE_IDLE, XR_SESSION_STATE_EXITING});
}

TEST_CASE("xr runtime: a session needs a graphics binding unless XR_MND_headless is enabled") {
  runtime_env();
  Instance instance({"XR_KHR_convert_timespec_time"});
  XrSessionCreateInfo info = xr_struct<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
  info.systemId = instance.system();
  XrSession s = XR_NULL_HANDLE;
  CHECK(xrCreateSession(instance.get(), &info, &s) == XR_ERROR_GRAPHICS_DEVICE_INVALID);
  info.systemId = 42;
  CHECK(xrCreateSession(instance.get(), &info, &s) == XR_ERROR_SYSTEM_INVALID);
}

TEST_CASE("xr runtime: destroyed, made-up and wrong-kind handles are XR_ERROR_HANDLE_INVALID") {
  runtime_env();
  Instance instance;
  auto session = std::make_unique<HeadlessSession>(instance);
  const XrSession s = session->get();
  const XrSpace local = session->reference_space(XR_REFERENCE_SPACE_TYPE_LOCAL);
  const XrSpace view = session->reference_space(XR_REFERENCE_SPACE_TYPE_VIEW);
  const TouchActions t = make_touch_actions(instance);
  REQUIRE(xrDestroySpace(view) == XR_SUCCESS);
  CHECK(xrDestroySpace(view) == XR_ERROR_HANDLE_INVALID);
  XrSpaceLocation location = xr_struct<XrSpaceLocation>(XR_TYPE_SPACE_LOCATION);
  CHECK(xrLocateSpace(view, local, kEpoch, &location) == XR_ERROR_HANDLE_INVALID);
  CHECK(xrLocateSpace(reinterpret_cast<XrSpace>(uintptr_t(0x7777)), local, kEpoch, &location) == XR_ERROR_HANDLE_INVALID);
  // A session handle where a space is expected, an action where an action set is.
  CHECK(xrLocateSpace(reinterpret_cast<XrSpace>(s), local, kEpoch, &location) == XR_ERROR_HANDLE_INVALID);
  XrActionCreateInfo ai = xr_struct<XrActionCreateInfo>(XR_TYPE_ACTION_CREATE_INFO);
  std::strcpy(ai.actionName, "extra");
  std::strcpy(ai.localizedActionName, "Extra");
  ai.actionType = XR_ACTION_TYPE_BOOLEAN_INPUT;
  XrAction a = XR_NULL_HANDLE;
  CHECK(xrCreateAction(reinterpret_cast<XrActionSet>(t.grip), &ai, &a) == XR_ERROR_HANDLE_INVALID);
  REQUIRE(xrDestroyAction(t.trigger) == XR_SUCCESS);
  XrActionStateGetInfo get = xr_struct<XrActionStateGetInfo>(XR_TYPE_ACTION_STATE_GET_INFO);
  get.action = t.trigger;
  XrActionStateFloat f = xr_struct<XrActionStateFloat>(XR_TYPE_ACTION_STATE_FLOAT);
  CHECK(xrGetActionStateFloat(s, &get, &f) == XR_ERROR_HANDLE_INVALID);
  REQUIRE(xrDestroyActionSet(t.set) == XR_SUCCESS);
  CHECK(xrCreateAction(t.set, &ai, &a) == XR_ERROR_HANDLE_INVALID);
  get.action = t.squeeze;  // destroyed with its set
  CHECK(xrGetActionStateFloat(s, &get, &f) == XR_ERROR_HANDLE_INVALID);
  // Destroying the session destroys its spaces.
  session.reset();
  CHECK(xrLocateSpace(local, local, kEpoch, &location) == XR_ERROR_HANDLE_INVALID);
  const XrSessionBeginInfo begin = stereo_begin();
  CHECK(xrBeginSession(s, &begin) == XR_ERROR_HANDLE_INVALID);
  CHECK(xrDestroySession(s) == XR_ERROR_HANDLE_INVALID);
}

TEST_CASE("xr runtime: wrong structure types are XR_ERROR_VALIDATION_FAILURE") {
  runtime_env();
  Instance instance;
  HeadlessSession session(instance);
  XrReferenceSpaceCreateInfo info = xr_struct<XrReferenceSpaceCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
  info.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_LOCAL;
  info.poseInReferenceSpace.orientation.w = 1.0f;
  XrSpace space = XR_NULL_HANDLE;
  CHECK(xrCreateReferenceSpace(session.get(), &info, &space) == XR_ERROR_VALIDATION_FAILURE);
  info.type = XR_TYPE_REFERENCE_SPACE_CREATE_INFO;
  info.poseInReferenceSpace.orientation.w = 2.0f;  // not a unit quaternion
  CHECK(xrCreateReferenceSpace(session.get(), &info, &space) == XR_ERROR_POSE_INVALID);
  XrEventDataBuffer event = xr_struct<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED);
  CHECK(xrPollEvent(instance.get(), &event) == XR_ERROR_VALIDATION_FAILURE);
  XrFrameState frame = xr_struct<XrFrameState>(XR_TYPE_FRAME_WAIT_INFO);
  CHECK(xrWaitFrame(session.get(), nullptr, &frame) == XR_ERROR_VALIDATION_FAILURE);
  XrSystemGetInfo get = xr_struct<XrSystemGetInfo>(XR_TYPE_SYSTEM_PROPERTIES);
  get.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
  XrSystemId system = 0;
  CHECK(xrGetSystem(instance.get(), &get, &system) == XR_ERROR_VALIDATION_FAILURE);
}

TEST_CASE("xr runtime: reference spaces, stage bounds, and the head as the VIEW space") {
  wedge::recordings::Recording r;
  r.source = "script";
  const Eigen::Quaterniond turned(Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitY()));  // facing -x
  wedge::recordings::HeadSample h0, h1;
  h0.t = 0.0;
  h0.pose.position = {0.1, 1.5, 0.2};
  h0.pose.orientation = turned;
  h1 = h0;
  h1.t = 0.05;
  h1.pose.position = {0.2, 1.5, 0.2};
  r.heads = {h0, h1};
  runtime_env({{"WEDGE_XR_REPLAY", write_test_recording("head.jsonl", r)}});
  Instance instance;
  HeadlessSession session(instance);
  uint32_t n = 0;
  REQUIRE(xrEnumerateReferenceSpaces(session.get(), 0, &n, nullptr) == XR_SUCCESS);
  CHECK(n == 3);
  std::vector<XrReferenceSpaceType> types(1);
  CHECK(xrEnumerateReferenceSpaces(session.get(), 1, &n, types.data()) == XR_ERROR_SIZE_INSUFFICIENT);
  XrExtent2Df bounds{};
  CHECK(xrGetReferenceSpaceBoundsRect(session.get(), XR_REFERENCE_SPACE_TYPE_STAGE, &bounds) == XR_SUCCESS);
  CHECK(bounds.width == 2.0f);
  CHECK(bounds.height == 2.0f);
  CHECK(xrGetReferenceSpaceBoundsRect(session.get(), XR_REFERENCE_SPACE_TYPE_LOCAL, &bounds) ==
        XR_SPACE_BOUNDS_UNAVAILABLE);
  // An extension's reference space (XR_MSFT_unbounded_reference_space is not offered): not a valid value.
  CHECK(xrGetReferenceSpaceBoundsRect(session.get(), XR_REFERENCE_SPACE_TYPE_UNBOUNDED_MSFT, &bounds) ==
        XR_ERROR_VALIDATION_FAILURE);

  const XrSpace local = session.reference_space(XR_REFERENCE_SPACE_TYPE_LOCAL);
  const XrSpace stage = session.reference_space(XR_REFERENCE_SPACE_TYPE_STAGE);
  const XrSpace view = session.reference_space(XR_REFERENCE_SPACE_TYPE_VIEW);
  XrSpaceLocation l = locate(stage, local, kEpoch);
  CHECK(l.locationFlags == kTracked);
  CHECK(l.pose.position.x == 0.0f);
  CHECK(l.pose.orientation.w == 1.0f);
  // Halfway between the two head samples: the position is blended.
  l = locate(view, local, sample_time(0.025));
  CHECK(l.locationFlags == kTracked);
  CHECK(l.pose.position.x == Approx(0.15).margin(1e-6));
  CHECK(l.pose.position.y == Approx(1.5).margin(1e-6));
  CHECK(std::abs(l.pose.orientation.y) == Approx(std::sqrt(0.5)).margin(1e-6));
  CHECK(xrLocateSpace(view, local, 0, &l) == XR_ERROR_TIME_INVALID);

  // The eyes: 0.0315 m either side along the head's x axis (here the tracking space's -z).
  XrViewLocateInfo info = xr_struct<XrViewLocateInfo>(XR_TYPE_VIEW_LOCATE_INFO);
  info.viewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
  info.displayTime = kEpoch;
  info.space = local;
  XrViewState state = xr_struct<XrViewState>(XR_TYPE_VIEW_STATE);
  REQUIRE(xrLocateViews(session.get(), &info, &state, 0, &n, nullptr) == XR_SUCCESS);
  CHECK(n == 2);
  std::vector<XrView> views(2, xr_struct<XrView>(XR_TYPE_VIEW));
  CHECK(xrLocateViews(session.get(), &info, &state, 1, &n, views.data()) == XR_ERROR_SIZE_INSUFFICIENT);
  REQUIRE(xrLocateViews(session.get(), &info, &state, 2, &n, views.data()) == XR_SUCCESS);
  CHECK(state.viewStateFlags == (XR_VIEW_STATE_POSITION_VALID_BIT | XR_VIEW_STATE_ORIENTATION_VALID_BIT |
                                 XR_VIEW_STATE_POSITION_TRACKED_BIT | XR_VIEW_STATE_ORIENTATION_TRACKED_BIT));
  CHECK(views[0].pose.position.x == Approx(0.1).margin(1e-6));
  CHECK(views[0].pose.position.z == Approx(0.2 + 0.0315).margin(1e-6));
  CHECK(views[1].pose.position.z == Approx(0.2 - 0.0315).margin(1e-6));
  for (const XrView& v : views) {
    CHECK(v.fov.angleLeft == Approx(-kPi / 4));
    CHECK(v.fov.angleRight == Approx(kPi / 4));
    CHECK(v.fov.angleUp == Approx(50 * kPi / 180));
    CHECK(v.fov.angleDown == Approx(-50 * kPi / 180));
  }
  info.displayTime = 0;
  CHECK(xrLocateViews(session.get(), &info, &state, 2, &n, views.data()) == XR_ERROR_TIME_INVALID);
}

TEST_CASE("xr runtime: without head samples the head stands behind the tracking origin, looking 35 degrees down") {
  // A person at a table: eyes half a metre behind the tracking origin (LOCAL) at its height, which is
  // 1.6 m above the STAGE floor; the view axis (-z) turned 35 degrees below the horizon.
  runtime_env();
  Instance instance;
  HeadlessSession session(instance);
  const XrSpaceLocation l = locate(session.reference_space(XR_REFERENCE_SPACE_TYPE_VIEW),
                                   session.reference_space(XR_REFERENCE_SPACE_TYPE_STAGE), frame_time(1000));
  CHECK(l.locationFlags == kTracked);
  CHECK(l.pose.position.x == 0.0f);
  CHECK(l.pose.position.y == Approx(1.6));
  CHECK(l.pose.position.z == Approx(0.5));
  const Eigen::Quaterniond q(l.pose.orientation.w, l.pose.orientation.x, l.pose.orientation.y, l.pose.orientation.z);
  const Eigen::Vector3d forward = q * Eigen::Vector3d(0, 0, -1);
  CHECK(std::asin(-forward.y()) * 180.0 / M_PI == Approx(35.0).margin(1e-4));
  CHECK(forward.x() == Approx(0.0).margin(1e-7));
}

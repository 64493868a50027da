// A well-behaved headless app from start to end, as an app written against the spec would drive it: the
// loop is led by the session state events, input is synced each frame, the grab vibrates the hand. It makes
// no deliberate mistakes, so it is also what runs under the Khronos core validation layer (CMakeLists.txt).
#include <cstdio>
#include <cstring>
#include <fstream>

#include "xr_test_support.hpp"

using namespace xrtest;
using wedge::recordings::Hand;

TEST_CASE("xr runtime: a headless app runs the recording from start to end led by the session state events") {
  wedge::recordings::Recording r;
  r.source = "script";
  for (int i = 0; i <= 45; ++i) {  // 0.5 s at 90 Hz; the right hand squeezes from 0.2 s to 0.3 s
    const double t = i / 90.0;
    r.hands.push_back(hand(t, Hand::Left, {-0.2, 1.0, -0.3}));
    r.hands.push_back(hand(t, Hand::Right, {0.2, 1.0 + 0.1 * t, -0.3}, Eigen::Quaterniond::Identity(),
                           t >= 0.2 && t < 0.3 ? 1.0 : 0.0));
  }
  const std::string log = temp_path("app_haptics.jsonl");
  std::remove(log.c_str());
  runtime_env({{"WEDGE_XR_REPLAY", write_test_recording("app.jsonl", r)}, {"WEDGE_XR_HAPTICS_LOG", log}});
  Instance instance({"XR_MND_headless"});
  const TouchActions t = make_touch_actions(instance);
  XrSessionCreateInfo create = xr_struct<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
  create.systemId = instance.system();
  XrSession session = XR_NULL_HANDLE;
  REQUIRE(xrCreateSession(instance.get(), &create, &session) == XR_SUCCESS);
  attach(session, t.set);
  XrReferenceSpaceCreateInfo space_info = xr_struct<XrReferenceSpaceCreateInfo>(XR_TYPE_REFERENCE_SPACE_CREATE_INFO);
  space_info.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_STAGE;
  space_info.poseInReferenceSpace.orientation.w = 1.0f;
  XrSpace stage = XR_NULL_HANDLE;
  REQUIRE(xrCreateReferenceSpace(session, &space_info, &stage) == XR_SUCCESS);
  const XrSpace right_grip = action_space(session, t.grip, t.right);

  bool running = false, exiting = false;
  int frames = 0, grabbed_frames = 0, tracked_frames = 0;
  std::vector<XrSessionState> states;
  while (!exiting && frames < 1000) {
    for (const XrEventDataBuffer& e : instance.poll_events()) {
      if (e.type != XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) continue;
      const XrSessionState state = reinterpret_cast<const XrEventDataSessionStateChanged&>(e).state;
      states.push_back(state);
      if (state == XR_SESSION_STATE_READY) {
        XrSessionBeginInfo begin = xr_struct<XrSessionBeginInfo>(XR_TYPE_SESSION_BEGIN_INFO);
        begin.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
        REQUIRE(xrBeginSession(session, &begin) == XR_SUCCESS);
        running = true;
      } else if (state == XR_SESSION_STATE_STOPPING) {
        REQUIRE(xrEndSession(session) == XR_SUCCESS);
        running = false;
      } else if (state == XR_SESSION_STATE_EXITING) {
        exiting = true;
      }
    }
    if (!running) continue;
    XrFrameState frame = xr_struct<XrFrameState>(XR_TYPE_FRAME_STATE);
    REQUIRE(xrWaitFrame(session, nullptr, &frame) == XR_SUCCESS);
    ++frames;
    const XrResult synced = sync(session, t.set);
    REQUIRE((synced == XR_SUCCESS || synced == XR_SESSION_NOT_FOCUSED));
    XrActionStateGetInfo get = xr_struct<XrActionStateGetInfo>(XR_TYPE_ACTION_STATE_GET_INFO);
    get.action = t.squeeze;
    get.subactionPath = t.right;
    XrActionStateFloat squeeze = xr_struct<XrActionStateFloat>(XR_TYPE_ACTION_STATE_FLOAT);
    REQUIRE(xrGetActionStateFloat(session, &get, &squeeze) == XR_SUCCESS);
    if (squeeze.isActive && squeeze.currentState > 0.9f) {
      ++grabbed_frames;
      XrHapticActionInfo haptic = xr_struct<XrHapticActionInfo>(XR_TYPE_HAPTIC_ACTION_INFO);
      haptic.action = t.haptic;
      haptic.subactionPath = t.right;
      XrHapticVibration v = xr_struct<XrHapticVibration>(XR_TYPE_HAPTIC_VIBRATION);
      v.amplitude = 0.5f;
      v.duration = XR_MIN_HAPTIC_DURATION;
      v.frequency = XR_FREQUENCY_UNSPECIFIED;
      REQUIRE(xrApplyHapticFeedback(session, &haptic, reinterpret_cast<const XrHapticBaseHeader*>(&v)) == XR_SUCCESS);
    }
    XrSpaceLocation location = xr_struct<XrSpaceLocation>(XR_TYPE_SPACE_LOCATION);
    REQUIRE(xrLocateSpace(right_grip, stage, frame.predictedDisplayTime, &location) == XR_SUCCESS);
    if (location.locationFlags == kTracked) ++tracked_frames;
  }
  CHECK(exiting);
  CHECK(states == std::vector<XrSessionState>{XR_SESSION_STATE_IDLE, XR_SESSION_STATE_READY,
                                              XR_SESSION_STATE_SYNCHRONIZED, XR_SESSION_STATE_VISIBLE,
                                              XR_SESSION_STATE_FOCUSED, XR_SESSION_STATE_VISIBLE,
                                              XR_SESSION_STATE_SYNCHRONIZED, XR_SESSION_STATE_STOPPING,
                                              XR_SESSION_STATE_IDLE, XR_SESSION_STATE_EXITING});
  CHECK(frames == 47);         // frames 0 .. 45 are within the recording, frame 46 is past its end
  CHECK(grabbed_frames == 9);  // samples 18 .. 26 (0.2 s to 0.29 s) squeeze
  CHECK(tracked_frames == 46);  // in frame 46 the session is STOPPING: not focused, the pose action inactive
  std::ifstream in(log);
  int lines = 0;
  for (std::string line; std::getline(in, line);) {
    CHECK(line.find("\"call\":\"apply\"") != std::string::npos);
    ++lines;
  }
  CHECK(lines == grabbed_frames);
  REQUIRE(xrDestroySession(session) == XR_SUCCESS);
}

// Haptics: every xrApplyHapticFeedback / xrStopHapticFeedback that reaches a hand is one JSON line in
// WEDGE_XR_HAPTICS_LOG, stamped with the frame time; calls on an unfocused session are refused.
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "xr_test_support.hpp"

using namespace xrtest;
using wedge::recordings::Hand;

namespace {

std::vector<nlohmann::json> read_log(const std::string& path) {
  std::vector<nlohmann::json> lines;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
  return lines;
}

XrResult apply(XrSession s, XrAction a, XrPath sub, float amplitude, XrDuration duration, float frequency) {
  XrHapticActionInfo info = xr_struct<XrHapticActionInfo>(XR_TYPE_HAPTIC_ACTION_INFO);
  info.action = a;
  info.subactionPath = sub;
  XrHapticVibration v = xr_struct<XrHapticVibration>(XR_TYPE_HAPTIC_VIBRATION);
  v.amplitude = amplitude;
  v.duration = duration;
  v.frequency = frequency;
  return xrApplyHapticFeedback(s, &info, reinterpret_cast<const XrHapticBaseHeader*>(&v));
}

XrResult stop(XrSession s, XrAction a, XrPath sub) {
  XrHapticActionInfo info = xr_struct<XrHapticActionInfo>(XR_TYPE_HAPTIC_ACTION_INFO);
  info.action = a;
  info.subactionPath = sub;
  return xrStopHapticFeedback(s, &info);
}

}  // namespace

TEST_CASE("xr runtime: haptic calls are logged one JSON line each, with the frame time and the hand") {
  wedge::recordings::Recording r;
  r.source = "script";
  for (double t : {0.0, 0.5, 1.0}) {
    r.hands.push_back(hand(t, Hand::Left, {-0.2, 1, -0.3}));
    r.hands.push_back(hand(t, Hand::Right, {0.2, 1, -0.3}));
  }
  const std::string log = temp_path("haptics.jsonl");
  std::remove(log.c_str());
  runtime_env({{"WEDGE_XR_REPLAY", write_test_recording("haptics_rec.jsonl", r)}, {"WEDGE_XR_HAPTICS_LOG", log}});
  Instance instance;
  HeadlessSession session(instance);
  const TouchActions t = make_touch_actions(instance);
  attach(session.get(), t.set);
  const XrSession s = session.get();
  // Before a sync the haptic action is inactive: the call reaches no hand.
  CHECK(apply(s, t.haptic, t.right, 1.0f, 1000, 0.0f) == XR_SUCCESS);
  for (int n = 0; n <= 45; ++n) session.wait_frame();  // frame 45: 0.5 s
  REQUIRE(sync(s, t.set) == XR_SUCCESS);
  CHECK(apply(s, t.haptic, t.right, 0.3f, 20'000'000, 160.0f) == XR_SUCCESS);
  CHECK(apply(s, t.haptic, XR_NULL_PATH, 0.5f, XR_MIN_HAPTIC_DURATION, XR_FREQUENCY_UNSPECIFIED) == XR_SUCCESS);
  session.wait_frame();
  CHECK(stop(s, t.haptic, t.left) == XR_SUCCESS);
  // Misuse: another action type, a wrong feedback struct, a subaction path the action lacks.
  CHECK(apply(s, t.squeeze, t.right, 1.0f, 1, 0.0f) == XR_ERROR_ACTION_TYPE_MISMATCH);
  XrHapticActionInfo info = xr_struct<XrHapticActionInfo>(XR_TYPE_HAPTIC_ACTION_INFO);
  info.action = t.haptic;
  XrHapticVibration wrong = xr_struct<XrHapticVibration>(XR_TYPE_HAPTIC_ACTION_INFO);
  CHECK(xrApplyHapticFeedback(s, &info, reinterpret_cast<const XrHapticBaseHeader*>(&wrong)) ==
        XR_ERROR_VALIDATION_FAILURE);
  CHECK(apply(s, t.haptic, instance.path("/user/head"), 1.0f, 1, 0.0f) == XR_ERROR_PATH_UNSUPPORTED);
  // Not focused any more: refused, and nothing logged.
  REQUIRE(xrRequestExitSession(s) == XR_SUCCESS);
  CHECK(apply(s, t.haptic, t.right, 1.0f, 1, 0.0f) == XR_SESSION_NOT_FOCUSED);
  CHECK(stop(s, t.haptic, t.right) == XR_SESSION_NOT_FOCUSED);

  const std::vector<nlohmann::json> lines = read_log(log);
  REQUIRE(lines.size() == 4);
  CHECK(lines[0] == nlohmann::json::parse(R"({"call":"apply","time_ns":1500000000,"t":0.5,"hand":"/user/hand/right",
                                               "amplitude":0.3,"duration_ns":20000000,"frequency":160.0})"));
  CHECK(lines[1]["hand"] == "/user/hand/left");  // no subaction path: every bound hand, in binding order
  CHECK(lines[2]["hand"] == "/user/hand/right");
  for (int i : {1, 2}) {
    CHECK(lines[i]["duration_ns"] == -1);
    CHECK(lines[i]["frequency"] == 0.0);
    CHECK(lines[i]["amplitude"] == 0.5);
  }
  CHECK(lines[3] == nlohmann::json::parse(R"({"call":"stop","time_ns":1511111111,"t":0.511111111,"hand":"/user/hand/left"})"));
  CHECK(lines[3]["time_ns"].get<int64_t>() == frame_time(46));
}

// The recording played back as grip and aim poses (action spaces located at any time, sub-frame times
// included), against the values the test computes itself from the samples it wrote.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "xr_test_support.hpp"

using namespace xrtest;
using wedge::recordings::Hand;

namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Quaterniond turn(double degrees, Eigen::Vector3d axis) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(degrees * kPi / 180.0, axis.normalized()));
}

// Spherical linear interpolation, written out (the shorter arc, as a unit quaternion).
Eigen::Quaterniond slerp(const Eigen::Quaterniond& a, Eigen::Quaterniond b, double u) {
  double dot = a.coeffs().dot(b.coeffs());
  if (dot < 0.0) {
    b.coeffs() = -b.coeffs();
    dot = -dot;
  }
  const double theta = std::acos(std::min(dot, 1.0));
  if (theta < 1e-9) return a;
  const double wa = std::sin((1.0 - u) * theta) / std::sin(theta), wb = std::sin(u * theta) / std::sin(theta);
  Eigen::Quaterniond q;
  q.coeffs() = wa * a.coeffs() + wb * b.coeffs();
  return q.normalized();
}

struct Expected {
  Eigen::Vector3d position;
  Eigen::Quaterniond orientation;
};

void check_pose(const XrSpaceLocation& l, const Expected& e) {
  CHECK(l.locationFlags == kTracked);
  CHECK(l.pose.position.x == Approx(e.position.x()).margin(2e-6));
  CHECK(l.pose.position.y == Approx(e.position.y()).margin(2e-6));
  CHECK(l.pose.position.z == Approx(e.position.z()).margin(2e-6));
  const Eigen::Quaterniond q(l.pose.orientation.w, l.pose.orientation.x, l.pose.orientation.y, l.pose.orientation.z);
  CHECK(std::abs(q.coeffs().dot(e.orientation.coeffs())) == Approx(1.0).margin(1e-6));
}

Expected at(const wedge::recordings::HandSample& s) { return {s.pose.position, s.pose.orientation}; }

Expected blend(const wedge::recordings::HandSample& a, const wedge::recordings::HandSample& b, double u) {
  return {a.pose.position + u * (b.pose.position - a.pose.position), slerp(a.pose.orientation, b.pose.orientation, u)};
}

}  // namespace

TEST_CASE("xr runtime: grip poses are the recorded hand poses, blended between samples, held across gaps") {
  wedge::recordings::Recording r;
  r.source = "script";
  const std::vector<wedge::recordings::HandSample> right = {
      hand(0.20, Hand::Right, {0.1, 1.0, -0.3}),
      hand(0.25, Hand::Right, {0.2, 1.1, -0.35}, turn(40, {1, 2, 3})),
      hand(0.30, Hand::Right, {0.3, 1.2, -0.4}, turn(80, {0, 1, 0})),
      hand(0.60, Hand::Right, {1.0, 1.0, 1.0}, turn(-30, {1, 0, 0})),  // 0.3 s later: a gap
      hand(0.70, Hand::Right, {1.1, 0.9, 1.0}, turn(10, {0, 0, 1})),   // exactly 0.1 s later: blended
  };
  const wedge::recordings::HandSample left_sample = hand(0.50, Hand::Left, {-0.2, 1.0, -0.3}, turn(20, {0, 1, 0}));
  r.hands = right;
  r.hands.push_back(left_sample);
  std::stable_sort(r.hands.begin(), r.hands.end(), [](const auto& a, const auto& b) { return a.t < b.t; });
  runtime_env({{"WEDGE_XR_REPLAY", write_test_recording("poses.jsonl", r)}});
  Instance instance;
  HeadlessSession session(instance);
  const TouchActions t = make_touch_actions(instance);
  attach(session.get(), t.set);
  // The recording's frame is LOCAL; STAGE's origin is on the floor 1.6 m below it (kStageDepth).
  const XrSpace stage = session.reference_space(XR_REFERENCE_SPACE_TYPE_LOCAL);
  const XrSpace floor = session.reference_space(XR_REFERENCE_SPACE_TYPE_STAGE);
  const XrSpace grip = action_space(session.get(), t.grip, t.right);
  const XrSpace left = action_space(session.get(), t.grip, t.left);
  // Before any xrSyncActions the pose action is inactive: nothing is located.
  CHECK(locate(grip, stage, sample_time(0.25)).locationFlags == 0);
  REQUIRE(sync(session.get(), t.set) == XR_SUCCESS);

  SECTION("untracked before the hand's first sample") {
    CHECK(locate(grip, stage, kEpoch).locationFlags == 0);
    CHECK(locate(grip, stage, sample_time(0.20) - 1).locationFlags == 0);
    CHECK(locate(left, stage, sample_time(0.45)).locationFlags == 0);
    check_pose(locate(left, stage, sample_time(0.50)), at(left_sample));
  }
  SECTION("at sample times, the samples") {
    for (const auto& s : right) {
      INFO("t = " << s.t);
      check_pose(locate(grip, stage, sample_time(s.t)), at(s));
      Expected above_floor = at(s);
      above_floor.position.y() += 1.6;
      check_pose(locate(grip, floor, sample_time(s.t)), above_floor);  // STAGE is LOCAL lowered by 1.6 m
    }
  }
  SECTION("between samples at most 0.1 s apart, blended at exactly the asked time") {
    const XrTime t0 = sample_time(0.20), t1 = sample_time(0.25);
    for (XrTime time : {t0 + 1, t0 + 12'345'678, (t0 + t1) / 2, t1 - 1}) {
      INFO("time " << time);
      check_pose(locate(grip, stage, time), blend(right[0], right[1], double(time - t0) / double(t1 - t0)));
    }
    const XrTime t3 = sample_time(0.60), t4 = sample_time(0.70);
    check_pose(locate(grip, stage, t3 + 30'000'000), blend(right[3], right[4], 30'000'000.0 / double(t4 - t3)));
    // The segment's velocity: (b - a) / dt.
    XrSpaceLocation l = xr_struct<XrSpaceLocation>(XR_TYPE_SPACE_LOCATION);
    XrSpaceVelocity v = xr_struct<XrSpaceVelocity>(XR_TYPE_SPACE_VELOCITY);
    l.next = &v;
    REQUIRE(xrLocateSpace(grip, stage, t0 + 20'000'000, &l) == XR_SUCCESS);
    CHECK((v.velocityFlags & XR_SPACE_VELOCITY_LINEAR_VALID_BIT) != 0);
    CHECK(v.linearVelocity.x == Approx(0.1 / 0.05).margin(1e-4));
    CHECK(v.linearVelocity.z == Approx(-0.05 / 0.05).margin(1e-4));
  }
  SECTION("held from the last sample across a gap longer than 0.1 s, and after the end") {
    for (double s : {0.3000001, 0.45, 0.5999999}) check_pose(locate(grip, stage, sample_time(s)), at(right[2]));
    check_pose(locate(grip, stage, sample_time(5.0)), at(right[4]));
  }
  SECTION("the aim pose is the grip pose times the documented offset") {
    const XrSpace aim = action_space(session.get(), t.aim, t.right);
    const Eigen::Quaterniond offset_q = turn(-30, {1, 0, 0});
    const Eigen::Vector3d offset_p(0.0, 0.0, -0.05);
    for (const auto& s : right)
      check_pose(locate(aim, stage, sample_time(s.t)),
                 {s.pose.position + s.pose.orientation * offset_p, s.pose.orientation * offset_q});
  }
  SECTION("poseInActionSpace is applied in the grip's frame") {
    XrActionSpaceCreateInfo info = xr_struct<XrActionSpaceCreateInfo>(XR_TYPE_ACTION_SPACE_CREATE_INFO);
    info.action = t.grip;
    info.subactionPath = t.right;
    info.poseInActionSpace.position = {0.0f, 0.0f, -0.1f};
    info.poseInActionSpace.orientation.w = 1.0f;
    XrSpace tip = XR_NULL_HANDLE;
    REQUIRE(xrCreateActionSpace(session.get(), &info, &tip) == XR_SUCCESS);
    const auto& s = right[2];
    check_pose(locate(tip, stage, sample_time(s.t)),
               {s.pose.position + s.pose.orientation * Eigen::Vector3d(0, 0, -0.1), s.pose.orientation});
    // The grip relative to the tip: the inverse offset.
    const XrSpaceLocation rel = locate(grip, tip, sample_time(0.9));
    CHECK(rel.pose.position.z == Approx(0.1).margin(1e-6));
  }
  SECTION("an action space of an action that is not active is not located") {
    REQUIRE(sync(session.get(), t.set, t.left) == XR_SUCCESS);  // only the left hand's bindings are active
    CHECK(locate(grip, stage, sample_time(0.25)).locationFlags == 0);
    CHECK(locate(left, stage, sample_time(0.55)).locationFlags == kTracked);
  }
}

TEST_CASE("xr runtime: without a recording the hands are never tracked") {
  runtime_env();
  Instance instance;
  HeadlessSession session(instance);
  const TouchActions t = make_touch_actions(instance);
  attach(session.get(), t.set);
  REQUIRE(sync(session.get(), t.set) == XR_SUCCESS);
  const XrSpace stage = session.reference_space(XR_REFERENCE_SPACE_TYPE_STAGE);
  for (XrPath hand_path : {t.left, t.right})
    for (XrTime time : {kEpoch, frame_time(100), frame_time(100000)})
      CHECK(locate(action_space(session.get(), t.grip, hand_path), stage, time).locationFlags == 0);
}

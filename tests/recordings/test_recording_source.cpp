// Recorded streams as input frames at step times (input/src/recording_source.cpp), and the input path's
// promises that need recordings: the rule (interpolate poses within gaps of 0.1 s, hold across longer
// ones, last sample for buttons, accelerometer samples each in its window), merging several recordings,
// the real CoreMotion trace through the whole gravity path against CoreMotion's own gravity, and no heap
// allocation per step once warmed up.
#include <catch2/catch.hpp>
#include <optional>
#include <atomic>
#include <cmath>
#include <cstdlib>

#include "allocation_counter.hpp"
#include "test_util.hpp"
#include "wedge/input/interaction.hpp"
#include "wedge/recordings/recording_source.hpp"
#include "wedge/mass.hpp"
#include "wedge/recordings/coremotion_csv.hpp"

using namespace wedge;
using namespace wedge::input;
using wedge::recordings::RecordingSource;
using recordings::HandSample;
using recordings::MotionSample;
using recordings::Recording;

namespace {
HandSample hs(double t, recordings::Hand hand, double x, double squeeze, std::uint32_t buttons = 0) {
  HandSample s;
  s.t = t;
  s.hand = hand;
  s.pose.position = Eigen::Vector3d(x, 1.0, 0.0);
  s.pose.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(x, Eigen::Vector3d::UnitY()));
  s.squeeze = squeeze;
  s.buttons = buttons;
  return s;
}
}  // namespace

TEST_CASE("recording source: interpolate within gaps, hold across them, buttons from the last sample", "[input]") {
  Recording r;
  r.hands = {hs(0.10, recordings::Hand::Right, 0.0, 0.2), hs(0.15, recordings::Hand::Right, 1.0, 0.9, 0x1),
             hs(0.40, recordings::Hand::Right, 2.0, 0.0)};
  RecordingSource src({r}, {"a.jsonl"});
  CHECK_FALSE(src.frame_at(0.05).hands[1].tracked);  // before the first sample
  CHECK_FALSE(src.frame_at(0.05).hands[0].tracked);  // no left hand at all
  const HandInput& mid = src.frame_at(0.12).hands[1];
  CHECK(mid.tracked);
  CHECK(mid.position.x() == Approx(0.4).epsilon(1e-12));  // 2/5 of the way from 0 to 1
  const double angle = Eigen::AngleAxisd(mid.orientation).angle();
  CHECK(angle == Approx(0.4).epsilon(1e-9));  // slerp: 2/5 of the way from 0 to 1 rad
  CHECK(mid.squeeze == 0.2);                  // the last sample's, not interpolated
  CHECK_FALSE(mid.mode4d);
  const HandInput& held = src.frame_at(0.30).hands[1];  // 0.25 s gap to the next sample: held
  CHECK(held.position.x() == 1.0);
  CHECK(held.squeeze == 0.9);
  CHECK(held.mode4d);  // A on the right controller
  CHECK(src.frame_at(0.5).hands[1].position.x() == 2.0);  // after the last sample: held
  CHECK_THROWS(src.frame_at(0.45));                       // time order
  CHECK(src.duration() == 0.40);
}

TEST_CASE("recording source: accelerometer samples each in their window, and merging recordings", "[input]") {
  Recording phone;
  for (int i = 0; i < 10; ++i) {
    MotionSample m;
    m.t = 0.013 * i;
    phone.motion.push_back(m);
  }
  Recording hands;
  hands.hands = {hs(0.0, recordings::Hand::Left, 0.0, 0.0, 0x100)};
  RecordingSource src({hands, phone}, {"hands.jsonl", "phone.jsonl"});
  std::size_t total = 0;
  double last = -1;
  for (int k = 0; k < 20; ++k) {
    const InputFrame& f = src.frame_at(k / 120.0);
    for (const MotionSample& m : f.motion) {
      CHECK(m.t > last);
      CHECK(m.t <= f.t);
      CHECK(m.t > (k - 1) / 120.0);
      last = m.t;
    }
    total += f.motion.size();
  }
  CHECK(total == 10);  // every sample exactly once
  CHECK(src.frame_at(1.0).hands[0].mode4d);  // X on the left controller
  CHECK(src.source_of_motion() == 1);
  CHECK(src.source_of_hand(0) == 0);
  CHECK_THROWS_WITH(RecordingSource({phone, phone}, {"p1.jsonl", "p2.jsonl"}),
                    Catch::Contains("p2.jsonl") && Catch::Contains("p1.jsonl") && Catch::Contains("accelerometer"));
  CHECK_THROWS_WITH(RecordingSource({hands, hands}, {"h1.jsonl", "h2.jsonl"}), Catch::Contains("left hand"));
}

TEST_CASE("the real CoreMotion trace tilts the world's gravity as CoreMotion's own estimate does", "[input][gravity]") {
  // recordings/coremotion/kinetic_tremor_data.csv: a hand-held phone, tilted and shaken. Through the
  // recording source and the input layer at 120 Hz, the world's gravity direction (in the slice) against
  // CoreMotion's fused gravity at the same time. The filter alone reaches 4.0 deg median, 8.0 deg p95
  // (test_gravity_filter.cpp); the layer may add only the step's resampling delay (< 1/120 s).
  const std::string csv = std::string(WEDGE_SOURCE_DIR) + "/recordings/coremotion/kinetic_tremor_data.csv";
  const std::vector<recordings::CoreMotionSample> truth = recordings::read_coremotion_csv(csv);
  RecordingSource src({recordings::import_coremotion_csv(csv)}, {csv});
  WorldSettings<4> s;
  s.gravity = Vec<4>(0, -9.81, 0, 0);
  World<4> world(s);
  Interaction<4> in(world, InteractionSettings<4>{});
  std::vector<double> errors;
  std::size_t j = 0;
  const double t0 = truth.front().time;
  for (int k = 0; k * (1.0 / 120.0) <= src.duration(); ++k) {
    const double t = k / 120.0;
    in.before_step(src.frame_at(t), 1.0 / 120.0);
    world.step(1.0 / 120.0);
    while (j + 1 < truth.size() && truth[j + 1].time - t0 <= t) ++j;
    if (t < 2.0) continue;  // the filter's start-up (tau = 5 s from the first sample's estimate)
    const Eigen::Vector3d g = world.gravity().head<3>().normalized(), want = truth[j].gravity.normalized();
    errors.push_back(std::acos(std::clamp(g.dot(want), -1.0, 1.0)) * 180 / M_PI);
  }
  REQUIRE(errors.size() > 800);  // 9.4 s of trace, from 2 s on, at 120 Hz
  std::sort(errors.begin(), errors.end());
  const double median = errors[errors.size() / 2], p95 = errors[errors.size() * 95 / 100];
  INFO("median " << median << " deg, p95 " << p95 << " deg");
  CHECK(median < 5.0);
  CHECK(p95 < 10.0);
  CHECK(world.gravity().norm() == Approx(9.81).epsilon(1e-12));
}

TEST_CASE("the input path makes no heap allocation per step once warmed up", "[input]") {
  // A 4D table: ground, a held tesseract knocked into two others, a phone tilting gravity, haptics.
  WorldSettings<4> s;
  s.gravity = Vec<4>(0, -9.81, 0, 0);
  World<4> world(s);
  BodyDef<4> ground;
  ground.type = BodyType::Static;
  ground.shape = std::make_shared<const Shape<4>>(Shape<4>::halfspace(Vec<4>(0, 1, 0, 0), 0.0));
  world.add_body(ground);
  for (double x : {0.0, 0.4, 0.65}) {
    BodyDef<4> d;
    const Vec<4> he = Vec<4>::Constant(0.1);
    d.shape = std::make_shared<const Shape<4>>(Shape<4>::box(he));
    const MassProperties<4> mp = box_mass_properties<4>(he, 500.0);
    d.mass = mp.mass;
    d.inertia = mp.inertia;
    d.position = Vec<4>(x, 0.1, 0, 0);
    world.add_body(d);
  }
  // 4 s at 120 Hz: grab at once and push the row along x at 0.5 m/s for 1.2 s (warm-up: the contacts form
  // and every buffer grows); then keep pushing against it while wiggling and turning the hand, in 4D
  // mode after 2 s, with the phone tilting and the tilt button on after 2.5 s.
  Recording r;
  for (int i = 0; i <= 480; ++i) {
    const double t = i / 120.0;
    HandSample h = hs(t, recordings::Hand::Right, 0.0, 1.0);
    h.pose.position = Eigen::Vector3d(std::min(0.5 * t, 0.6) + 0.01 * std::sin(7 * t), 0.1 + 0.01 * std::sin(3 * t), 0.0);
    h.pose.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3 * std::sin(t), Eigen::Vector3d::UnitZ()));
    h.mode4d = t > 2.0;
    r.hands.push_back(h);
    MotionSample m;
    m.t = t;
    m.acceleration = Eigen::Vector3d(0.1 * std::sin(t), -1.0, 0.0);
    m.has_rotation_rate = true;
    m.tilt = t > 2.5;
    r.motion.push_back(m);
  }
  RecordingSource src({r}, {"scripted"});
  Interaction<4> in(world, InteractionSettings<4>{});
  long allocations = 0;
  int pulses = 0;
  long stage[3] = {0, 0, 0};
  for (int k = 0; k < 480; ++k) {
    std::optional<allocation_counter::Armed> armed;
    if (k >= 240) armed.emplace();  // warmed up: buffers have grown to their working size
    long before = allocation_counter::count();
    in.before_step(src.frame_at(k / 120.0), 1.0 / 120.0);
    stage[0] += allocation_counter::count() - before;
    before = allocation_counter::count();
    world.step(1.0 / 120.0);
    stage[1] += allocation_counter::count() - before;
    before = allocation_counter::count();
    in.after_step();
    stage[2] += allocation_counter::count() - before;
    armed.reset();
    pulses += int(in.pulses().size());
  }
  allocations = stage[0] + stage[1] + stage[2];
  CHECK(in.held(1));
  CHECK(world.body(BodyId{3}).center[0] > 0.7);  // the push reached the far tesseract
  INFO("pulses " << pulses << "; allocations in before_step " << stage[0] << ", step " << stage[1] << ", after_step "
                    << stage[2]);
  CHECK(allocations == 0);
}

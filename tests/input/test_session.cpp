// The input session (input/src/session.cpp) and the streaming recording writer, against what a live
// session promises: the steps a clock pays for run at t = k h with the frame of that time, and a session
// recorded line by line while it runs replays (through recordings::RecordingSource, as `wedge replay`
// reads files) to the same state bit for bit, with the same grabs, releases and pulses at the same steps.
// A recording cut off mid-write keeps every whole line.
#include <catch2/catch.hpp>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "test_util.hpp"
#include "wedge/input/session.hpp"
#include "wedge/mass.hpp"
#include "wedge/recordings/recording.hpp"
#include "wedge/recordings/recording_source.hpp"

using namespace wedge;
using namespace wedge::input;
namespace fs = std::filesystem;

namespace {

constexpr double kH = 1.0 / 120.0;

struct TempFile {
  std::string path;
  TempFile() {
    std::string templ = (fs::temp_directory_path() / "wedge_session_test_XXXXXX").string();
    const int fd = ::mkstemp(templ.data());
    REQUIRE(fd >= 0);
    ::close(fd);
    path = templ;
  }
  ~TempFile() { std::remove(path.c_str()); }
};

template <int N>
Vec<N> at(double x, double y) {
  Vec<N> v = Vec<N>::Zero();
  v[0] = x;
  v[1] = y;
  return v;
}

// A cube resting on the ground, to be grabbed, lifted, knocked down and thrown.
template <int N>
World<N> table(BodyId& cube) {
  WorldSettings<N> s;
  s.gravity = at<N>(0, -9.81);
  World<N> world(s);
  BodyDef<N> g;
  g.type = BodyType::Static;
  g.shape = std::make_shared<const Shape<N>>(Shape<N>::halfspace(at<N>(0, 1), 0.0));
  world.add_body(g);
  BodyDef<N> d;
  const Vec<N> he = Vec<N>::Constant(0.1);
  d.shape = std::make_shared<const Shape<N>>(Shape<N>::box(he));
  const MassProperties<N> mp = box_mass_properties<N>(he, 500.0);
  d.mass = mp.mass;
  d.inertia = mp.inertia;
  d.position = at<N>(0, 0.1);
  cube = world.add_body(d);
  return world;
}

// The right hand's script: reach the cube, squeeze at 0.2 s, lift to 0.5 m, turn, strike the ground hard
// at 0.9 s, lift, swing sideways and let go at 1.4 s.
HandInput scripted_hand(double t) {
  HandInput h;
  h.tracked = true;
  double y = 0.1;
  if (t > 0.25) y = std::min(0.1 + 1.5 * (t - 0.25), 0.5);
  if (t > 0.7) y = std::max(0.5 - 3.0 * (t - 0.7), 0.02);
  if (t > 1.0) y = 0.02 + 1.0 * (t - 1.0);
  const double x = t > 1.1 ? 2.0 * (t - 1.1) : 0.0;
  h.position = Eigen::Vector3d(x, y, 0.0);
  h.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.8 * std::min(t, 0.6), Eigen::Vector3d(0.3, 1.0, 0.2).normalized()));
  h.squeeze = t >= 0.2 && t < 1.4 ? 1.0 : 0.0;
  h.buttons = t > 0.3 && t < 0.6 ? recordings::kButtonA : 0;
  h.mode4d = h.buttons != 0;
  return h;
}

template <int N>
SessionSettings<N> settings() {
  SessionSettings<N> s;
  s.timestep = kH;
  return s;
}

}  // namespace

TEST_CASE("input session: advance runs the steps a clock pays for, each with the frame of its start time", "[input]") {
  BodyId cube;
  World<3> world = table<3>(cube);
  SessionSettings<3> s = settings<3>();
  s.timestep = 0.01;
  s.max_steps_per_advance = 16;
  Session<3> session(world, s);
  std::vector<double> asked;
  InputFrame frame;
  auto frame_at = [&](double t) -> const InputFrame& {
    asked.push_back(t);
    frame.t = t;
    return frame;
  };
  CHECK(session.advance(0.025, frame_at) == 2);  // 0.025 s pays for two 0.01 s steps, 0.005 s owed
  CHECK(session.advance(0.006, frame_at) == 1);  // 0.011 s owed: one more
  CHECK(session.advance(0.0, frame_at) == 0);
  REQUIRE(asked.size() == 3);
  for (std::size_t k = 0; k < asked.size(); ++k) CHECK(asked[k] == double(k) * 0.01);
  CHECK(world.step_count() == 3);
  CHECK(session.time() == 3 * 0.01);
  // A clock far ahead (a stall): at most max_steps_per_advance run and the rest of the debt is dropped.
  CHECK(session.advance(10.0, frame_at) == 16);
  CHECK(session.advance(0.0, frame_at) == 0);
  s.timestep = 0.0;
  CHECK_THROWS_WITH(Session<3>(world, s), Catch::Contains("timestep must be finite and > 0"));
}

TEMPLATE_TEST_CASE("input session: a live session recorded line by line replays to the same state, bit for bit",
                   "[input][recordings]", D3, D4) {
  constexpr int N = TestType::value;
  TempFile file;
  BodyId cube;
  World<N> live = table<N>(cube);
  Session<N> session(live, settings<N>());
  std::vector<InteractionEvent<N>> events;
  std::vector<HapticPulse<N>> pulses;
  {
    recordings::RecordingWriter writer(file.path, "test");
    session.set_observer([&](const InputFrame& f) { writer.write_frame(f); });
    InputFrame frame;
    auto frame_at = [&](double t) -> const InputFrame& {
      frame.t = t;
      frame.hands[1] = scripted_hand(t);
      return frame;
    };
    // A display clock at 90 Hz against 120 Hz physics: one or two steps per frame.
    for (int f = 0; f < 150; ++f) {
      session.advance(1.0 / 90.0, frame_at);
      events.insert(events.end(), session.events().begin(), session.events().end());
      pulses.insert(pulses.end(), session.pulses().begin(), session.pulses().end());
      session.clear_output();
    }
    writer.close();
    CHECK(writer.samples() == session.step_count());
  }
  // What must have happened: a grab of the cube, a pulse when it struck the ground while held (its
  // amplitude from the approach speed by the haptics rule), a release that threw it sideways.
  REQUIRE(events.size() == 2);
  CHECK(events[0].kind == InteractionEvent<N>::Kind::Grab);
  CHECK(events[0].body == cube);
  CHECK(events[1].kind == InteractionEvent<N>::Kind::Release);
  CHECK(events[1].t == Approx(1.4).margin(kH));
  CHECK(events[1].velocity[0] > 1.0);  // swung at 2 m/s along x
  REQUIRE(pulses.size() >= 1);
  CHECK(pulses[0].t > 0.7);
  CHECK(pulses[0].approach_speed > 1.0);
  CHECK(pulses[0].amplitude == pulse_amplitude(pulses[0].approach_speed, 2.0, 0.1));

  // The replay: the file read back as `wedge replay` reads it.
  BodyId cube2;
  World<N> replayed = table<N>(cube2);
  Session<N> again(replayed, settings<N>());
  recordings::RecordingSource source({recordings::read_recording(file.path)}, {file.path});
  std::vector<InteractionEvent<N>> events2;
  std::vector<HapticPulse<N>> pulses2;
  while (again.step_count() < session.step_count()) {
    again.step(source.frame_at(again.time()));
    events2.insert(events2.end(), again.events().begin(), again.events().end());
    pulses2.insert(pulses2.end(), again.pulses().begin(), again.pulses().end());
    again.clear_output();
  }
  CHECK(replayed.state_hash() == live.state_hash());
  REQUIRE(events2.size() == events.size());
  for (std::size_t i = 0; i < events.size(); ++i) {
    CHECK(events2[i].kind == events[i].kind);
    CHECK(events2[i].step == events[i].step);
  }
  REQUIRE(pulses2.size() == pulses.size());
  for (std::size_t i = 0; i < pulses.size(); ++i) {
    CHECK(pulses2[i].step == pulses[i].step);
    CHECK(pulses2[i].amplitude == pulses[i].amplitude);
  }
}

TEST_CASE("recording writer: a session cut off mid-line keeps every whole line, and bad samples are refused",
          "[recordings]") {
  TempFile file;
  {
    recordings::RecordingWriter writer(file.path, "xr");
    for (int k = 0; k < 5; ++k) {
      recordings::HandSample s;
      s.t = k * 0.01;
      s.pose.position = Eigen::Vector3d(0.1 * k, 1.0, 0.0);
      s.squeeze = 0.5;
      writer.write(s);
      recordings::HeadSample g;
      g.t = s.t;
      writer.write(g);
    }
    // Each line is on disk as soon as it is written (no buffer to lose): read it while the writer is open.
    CHECK(recordings::read_recording(file.path).hands.size() == 5);
    recordings::HandSample back;
    back.t = 0.01;
    CHECK_THROWS_WITH(writer.write(back), Catch::StartsWith(file.path + ": cannot write hand sample 11: time goes backwards"));
    recordings::HandSample bad;
    bad.t = 1.0;
    bad.trigger = 1.5;
    CHECK_THROWS_WITH(writer.write(bad), Catch::Contains("trigger = 1.5 is outside [0, 1]"));
  }  // (destroyed without close(): as a crash would leave it)
  std::ofstream(file.path, std::ios::app) << R"({"t":0.05,"type":"hand","hand":"ri)";  // a torn last line
  const recordings::Recording r = recordings::read_recording(file.path);
  CHECK(r.source == "xr");
  CHECK(r.hands.size() == 5);
  CHECK(r.heads.size() == 5);
  CHECK(r.hands[4].pose.position.x() == 0.4);
  REQUIRE(r.warnings.size() == 1);
  CHECK_THAT(r.warnings[0], Catch::Contains("torn last line"));
  CHECK_THROWS_WITH(recordings::RecordingWriter("/nonexistent/dir/x.jsonl", "xr"),
                    Catch::StartsWith("/nonexistent/dir/x.jsonl: cannot create the recording"));
}

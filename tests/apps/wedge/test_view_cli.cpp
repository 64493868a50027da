// `wedge view` run as a user would, headless under Xvfb (Debian's xvfb; Mesa's software GL): the window's
// screenshot against the offscreen renderer's picture of the same slice (`wedge render --steps 0`, the
// same camera fit and size), body by body, outside the panel; --w choosing which bodies are drawn as the
// slicer predicts; and no display: exit 2 naming DISPLAY, nothing written.
#include <png.h>

#include <catch2/catch.hpp>
#include <algorithm>
#include <array>
#include <cstdio>
#include <sstream>
#include <string>

#include "cli_runner.hpp"
#include "png_pixels.hpp"

using namespace cli_runner;

constexpr int kViewLeft = 316;  // px: the 3D view starts right of the panel; pixels are looked for there

namespace {

// Three tesseracts of side 1 in pure red, green and blue along x; the blue one at w = `blue_w`.
std::string scene(double blue_w) {
  return R"({"dim": 4, "bodies": [
    {"name": "r", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5, 0.5]}, "position": [-1.5, 0, 0, 0], "color": [1, 0, 0]},
    {"name": "g", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5, 0.5]}, "position": [0, 0, 0, 0], "color": [0, 1, 0]},
    {"name": "b", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5, 0.5]}, "position": [1.5, 0, 0, )" +
         std::to_string(blue_w) + R"(], "color": [0, 0, 1]}]})";
}

// The viewer's markers: the right hand (magenta), a haptic flash (yellow), contact points (orange).
bool magenta(const std::uint8_t* p) { return p[0] > p[1] + 80 && p[2] > p[1] + 60; }
bool yellow(const std::uint8_t* p) { return p[0] > 150 && p[1] > 0.8 * p[0] && p[2] < 60; }
bool orange(const std::uint8_t* p) { return p[0] > 150 && p[1] > 0.3 * p[0] && p[1] < 0.65 * p[0] && p[2] < 40; }

// Pixels where one channel dominates (a lit body of that pure colour), counted from column from_x on.
std::array<long, 3> coverage(const fs::path& file, int from_x) {
  const Image im = load(file);
  return {find(im, pure(0), from_x).count, find(im, pure(1), from_x).count, find(im, pure(2), from_x).count};
}
Blob blob(const fs::path& file, int channel) { return find(load(file), pure(channel), kViewLeft); }

// Runs `wedge ARGS` with DISPLAY set to a fresh Xvfb server (the server picks a free display number).
Result under_xvfb(const TempDir& dir, const std::string& args) {
  return dir.shell("rm -f display; Xvfb -displayfd 5 -screen 0 1400x900x24 -nolisten tcp 5>display 2>/dev/null & x=$!; "
                   "i=0; while [ ! -s display ] && [ $i -lt 100 ]; do sleep 0.05; i=$((i+1)); done; "
                   "DISPLAY=:$(cat display) \"$WEDGE\" " + args + "; rc=$?; kill $x; exit $rc");
}

// Frame 1 of s.json (step 0) as the viewer draws it, and where the body of pure colour `channel` is in it.
Blob at_start(const TempDir& dir, int channel) {
  const Result first = under_xvfb(dir, "view s.json --frames 1 --screenshot f1.png --size 800x450");
  REQUIRE(first.code == 0);
  const Blob b = blob(dir.path() / "f1.png", channel);
  REQUIRE(b.count > 500);
  return b;
}

// One line of a --mouse script: frame, cursor, and further fields (",\"left\":true", ..).
std::string mouse_line(int frame, double x, double y, const std::string& more = "") {
  std::string line = "{\"frame\":";  // (piecewise: GCC 12 warns falsely on "..." + std::string)
  line += std::to_string(frame);
  line += ",\"x\":";
  line += std::to_string(x);
  line += ",\"y\":";
  line += std::to_string(y);
  line += more;
  line += "}\n";
  return line;
}

}  // namespace

TEST_CASE("wedge view: the window shows what the offscreen renderer shows", "[cli][view]") {
  TempDir dir;
  dir.write("s.json", scene(0.0));
  const Result v = under_xvfb(dir, "view s.json --frames 1 --screenshot shot.png --size 800x450");
  INFO(v.err);
  REQUIRE(v.code == 0);
  // The 3D view is the window right of the panel, x >= 316 px: 484 x 450, which `render` draws alike.
  const Result r = dir.run("render s.json --steps 0 --out frames --size 484x450");
  REQUIRE(r.code == 0);
  // Same camera fit, same size, the same renderer on Mesa's software rasteriser: the counts agree to 1%.
  const std::array<long, 3> shot = coverage(dir.path() / "shot.png", 316);
  const std::array<long, 3> offscreen = coverage(dir.path() / "frames" / "frame_00000.png", 0);
  for (int c = 0; c < 3; ++c) {
    INFO("colour " << c << ": window " << shot[std::size_t(c)] << " px, offscreen " << offscreen[std::size_t(c)] << " px");
    CHECK(offscreen[std::size_t(c)] > 500);
    CHECK(std::abs(shot[std::size_t(c)] - offscreen[std::size_t(c)]) <= offscreen[std::size_t(c)] / 100 + 5);
  }
}

TEST_CASE("wedge view: --w draws the bodies the slice meets", "[cli][view]") {
  TempDir dir;
  dir.write("s.json", scene(0.8));  // blue at w = 0.8: beyond its half size from w = 0
  const Result at0 = under_xvfb(dir, "view s.json --frames 1 --screenshot a.png --size 800x450");
  const Result at8 = under_xvfb(dir, "view s.json --w 0.8 --frames 1 --screenshot b.png --size 800x450");
  REQUIRE(at0.code == 0);
  REQUIRE(at8.code == 0);
  const std::array<long, 3> a = coverage(dir.path() / "a.png", 316), b = coverage(dir.path() / "b.png", 316);
  CHECK(a[2] == 0);    // w = 0: red and green, no blue
  CHECK(a[0] > 500);
  CHECK(b[0] == 0);    // w = 0.8: only blue (|0 - 0.8| > 0.5 for red and green)
  CHECK(b[1] == 0);
  CHECK(b[2] > 500);
}

TEST_CASE("wedge view: without a display it exits 2 naming DISPLAY", "[cli][view]") {
  TempDir dir;
  dir.write("s.json", scene(0.0));
  const Result r = dir.shell("unset DISPLAY WAYLAND_DISPLAY; \"$WEDGE\" view s.json --frames 1 --screenshot x.png");
  CHECK(r.code == 2);
  CHECK(r.err.find("DISPLAY") != std::string::npos);
  CHECK(r.err.find("s.json") != std::string::npos);
  CHECK_FALSE(fs::exists(dir.path() / "x.png"));
  const Result no_frames = dir.run("view s.json --screenshot x.png");
  CHECK(no_frames.code == 2);
  CHECK(no_frames.err.find("--frames") != std::string::npos);
  const Result bad_level = dir.run("view s.json --play-subdivisions 0 --frames 1");
  CHECK(bad_level.code == 2);
  CHECK(bad_level.err.find("s.json: --play-subdivisions must be an integer in 1..64") != std::string::npos);
  const Result same_file = dir.run("view s.json --frames 1 --events x.jsonl --record x.jsonl");
  CHECK(same_file.code == 2);
  CHECK(same_file.err.find("s.json: --events must name a file of its own") != std::string::npos);
  CHECK_FALSE(fs::exists(dir.path() / "x.jsonl"));
}

TEST_CASE("wedge view: a scripted mouse grabs a body, drags it and throws it", "[cli][view]") {
  TempDir dir;
  dir.write("s.json", scene(0.0));  // no gravity: a thrown body keeps going
  const Blob red = at_start(dir, 0), green = blob(dir.path() / "f1.png", 1);
  // Press on the red tesseract's centre of picture at frame 2, drag 100 px up over frames 3..40, let go at
  // frame 41 (the hand then moves at ~2.6 px per frame).
  std::string script;
  for (int f = 2; f <= 40; ++f) script += mouse_line(f, red.x, red.y - 100.0 * (f - 2) / 38, ",\"left\":true");
  script += mouse_line(41, red.x, red.y - 100);
  dir.write("drag.jsonl", script);
  const Result held = under_xvfb(dir, "view s.json --mouse drag.jsonl --frames 41 --screenshot f41.png --size 800x450");
  const Result later = under_xvfb(dir, "view s.json --mouse drag.jsonl --frames 55 --screenshot f55.png --size 800x450");
  INFO(held.err << later.err);
  REQUIRE(held.code == 0);
  REQUIRE(later.code == 0);
  const Blob red41 = blob(dir.path() / "f41.png", 0), red55 = blob(dir.path() / "f55.png", 0);
  const Blob green41 = blob(dir.path() / "f41.png", 1);
  INFO("red centroid y: " << red.y << " -> " << red41.y << " (frame 41) -> " << red55.y << " (frame 55)");
  // The grabbed point followed the cursor up (the spring lags a little: at least 70 of the 100 px).
  CHECK(red.y - red41.y > 70.0);
  CHECK(std::abs(red41.x - red.x) < 15.0);
  // Released while moving: it flies on upward (or out of the picture) without the hand.
  CHECK((red55.y < red41.y - 10.0 || red55.count < red41.count / 2));
  // Nobody touched the green one.
  CHECK(std::abs(green41.count - green.count) <= green.count / 100);
  CHECK(std::abs(green41.x - green.x) < 0.5);
}

TEST_CASE("wedge view --record: a mouse session replays bit for bit with wedge replay", "[cli][view][replay]") {
  TempDir dir;
  dir.write("s.json", scene(0.0));
  const Blob red = at_start(dir, 0);
  // Grab the red tesseract, drag it up and to the right with a turn (right button), let go.
  std::string script;
  for (int f = 2; f <= 30; ++f)
    script += mouse_line(f, red.x + 2.0 * (f - 2), red.y - 2.0 * (f - 2),
                         std::string(",\"left\":true,\"right\":") + (f > 15 ? "true" : "false"));
  script += mouse_line(31, red.x + 60, red.y - 58);
  dir.write("drag.jsonl", script);
  const Result v = under_xvfb(dir, "view s.json --mouse drag.jsonl --frames 50 --record session.jsonl --hash --size 800x450");
  INFO(v.err);
  REQUIRE(v.code == 0);
  // "98 steps; state hash H": 49 frames advanced, two steps of 1/120 s each.
  const std::size_t at = v.out.find(" steps; state hash ");
  REQUIRE(at != std::string::npos);
  const long steps = std::stol(v.out.substr(0, at));
  const std::string hash = v.out.substr(at + 19, 16);
  CHECK(steps == 98);
  char until[32];  // (all the digits: --until T runs ceil(T / h) steps)
  std::snprintf(until, sizeof until, "%.17g", double(steps) / 120.0);
  const Result r = dir.run(std::string("replay s.json session.jsonl --until ") + until +
                           " --every 1000000 --hash --events events.jsonl");
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.lines().back()["state_hash"].get<std::string>() == hash);
  // What happened, read back: one grab of the red tesseract, one release, and it moved.
  const std::string events = read_file(dir.path() / "events.jsonl");
  CHECK(events.find("\"type\":\"grab\"") != std::string::npos);
  CHECK(events.find("\"body\":\"r\"") != std::string::npos);
  CHECK(events.find("\"type\":\"release\"") != std::string::npos);
}

// Nothing lost on a crash, as for `wedge xr --record` (test_xr_cli.cpp): a viewer session recording a
// scripted mouse and killed with SIGKILL once its file holds 150 lines leaves bytes that are exactly the
// start of the same session run to its end (the script and --frames fix every step), and its complete
// lines replay.
TEST_CASE("wedge view --record: a session killed with SIGKILL leaves every complete line, and they replay",
          "[cli][view][replay]") {
  TempDir dir;
  dir.write("s.json", scene(0.0));
  std::string script;  // the cursor sweeping, the left button pressed for half of every 100 frames
  for (int f = 2; f < 300; ++f)
    script += mouse_line(f, 400 + f % 50, 200, f % 100 < 50 ? ",\"left\":true" : "");
  dir.write("m.jsonl", script);
  const std::string view = "view s.json --mouse m.jsonl --frames 300 --size 800x450 --record ";
  const Result full = under_xvfb(dir, view + "full.jsonl");
  INFO(full.err);
  REQUIRE(full.code == 0);
  const Result killed = under_xvfb(dir, view + "killed.jsonl & p=$!; n=0; "
                                          "while [ $(cat killed.jsonl 2>/dev/null | wc -l) -lt 150 ] && [ $n -lt 6000 ]; do "
                                          "sleep 0.01; n=$((n+1)); done; kill -KILL $p; wait $p; (exit $?)");
  CHECK(killed.code == 128 + 9);
  const std::string whole = read_file(dir.path() / "full.jsonl"), cut = read_file(dir.path() / "killed.jsonl");
  REQUIRE(std::count(cut.begin(), cut.end(), '\n') >= 150);
  REQUIRE(cut.size() < whole.size());                // killed before the end
  CHECK(whole.compare(0, cut.size(), cut) == 0);     // every byte written is the full run's
  const std::size_t complete = cut.rfind('\n') + 1;  // the complete lines' bytes
  const Result replayed = dir.run("replay s.json killed.jsonl --hash");
  INFO(replayed.err);
  CHECK(replayed.code == 0);
  CHECK((complete == cut.size()) == (replayed.err.find("torn last line") == std::string::npos));
}

TEST_CASE("wedge view --replay draws the recorded hand as a marker", "[cli][view][replay]") {
  TempDir dir;
  dir.write("s.json", scene(0.0));
  // A right hand held still in front of the green tesseract (between it and the camera), not squeezing.
  std::string rec = R"({"format":"wedge-recording","version":1,"source":"script","units":{"time":"s","position":"m",)"
                    R"("acceleration":"g","rotation_rate":"rad/s"},"conventions":{}})"
                    "\n";
  for (int i = 0; i <= 20; ++i)
    rec += R"({"t":)" + std::to_string(i * 0.05) +
           R"(,"type":"hand","hand":"right","position":[0,0,0.9],"orientation":[1,0,0,0],"squeeze":0,)"
           R"("trigger":0,"buttons":[],"mode4d":false})" "\n";
  dir.write("hand.jsonl", rec);
  const Result without = under_xvfb(dir, "view s.json --frames 5 --screenshot a.png --size 800x450");
  const Result with = under_xvfb(dir, "view s.json --replay hand.jsonl --frames 5 --screenshot b.png --size 800x450");
  INFO(with.err);
  REQUIRE(without.code == 0);
  REQUIRE(with.code == 0);
  // Magenta (red and blue well above green) appears only with the hand.
  CHECK(find(load(dir.path() / "a.png"), magenta, kViewLeft).count == 0);
  CHECK(find(load(dir.path() / "b.png"), magenta, kViewLeft).count > 15);
}

TEST_CASE("wedge view: the phone control tilts gravity, and a recorded session replays it", "[cli][view][replay]") {
  TempDir dir;
  // Two tesseracts resting on a ground under gravity along -y.
  dir.write("g.json", R"({"dim": 4, "gravity": [0, -9.81, 0, 0], "bodies": [
    {"name": "ground", "static": true, "shape": {"type": "halfspace", "normal": [0, 1, 0, 0], "offset": 0}},
    {"name": "r", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5, 0.5]}, "position": [-1, 0.5, 0, 0], "color": [1, 0, 0]},
    {"name": "g", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5, 0.5]}, "position": [1, 0.5, 0, 0], "color": [0, 1, 0]}]})");
  // The phone turned 30 degrees counterclockwise at frame 2, the tilt toward w switched on at frame 60.
  dir.write("tilt.jsonl", "{\"frame\":2,\"x\":0,\"y\":0,\"roll\":30}\n{\"frame\":60,\"x\":0,\"y\":0,\"tilt_w\":true}\n");
  const Result v = under_xvfb(dir, "view g.json --mouse tilt.jsonl --frames 100 --record phone.jsonl --hash --size 800x450");
  INFO(v.err);
  REQUIRE(v.code == 0);
  const std::size_t at = v.out.find(" steps; state hash ");
  REQUIRE(at != std::string::npos);
  const long steps = std::stol(v.out.substr(0, at));
  char until[32];
  std::snprintf(until, sizeof until, "%.17g", double(steps) / 120.0);
  const Result r = dir.run(std::string("replay g.json phone.jsonl --until ") + until + " --hash");
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto lines = r.lines();
  CHECK(lines.back()["state_hash"].get<std::string>() == v.out.substr(at + 19, 16));  // bit for bit
  // Gravity as the replay reports it: 30 degrees from -y toward -x in the slice (the accelerometer-only
  // filter's 0.25 s has had over a second), and 15 degrees toward +w once the tilt is on.
  auto gravity_at = [&](double t) {
    for (const json& s : lines)
      if (s.contains("time") && s["time"].get<double>() >= t) return s["gravity"].get<std::vector<double>>();
    return lines[lines.size() - 2]["gravity"].get<std::vector<double>>();
  };
  const std::vector<double> g1 = gravity_at(0.95);
  CHECK(std::atan2(-g1[0], -g1[1]) * 180 / M_PI == Approx(30.0).margin(0.5));
  CHECK(g1[3] == 0.0);
  const std::vector<double> g2 = gravity_at(1.6);
  CHECK(std::atan2(g2[3], std::sqrt(g2[0] * g2[0] + g2[1] * g2[1] + g2[2] * g2[2])) * 180 / M_PI ==
        Approx(15.0).margin(1e-6));
}

TEST_CASE("wedge view: a push shows the hand marker, flashes it at the haptic pulse, and --events lists it",
          "[cli][view]") {
  TempDir dir;
  dir.write("s.json", scene(0.0));  // no gravity; red 0.5 m left of green
  const Blob red = at_start(dir, 0);
  // Grab the red tesseract at frame 2, push it right into the green one over frames 3..40, let go at 60.
  std::string script;
  for (int f = 2; f <= 40; ++f)
    script += mouse_line(f, red.x + 110.0 * (f - 2) / 38, red.y + 20.0 * (f - 2) / 38, ",\"left\":true");
  script += mouse_line(60, red.x + 110, red.y + 20);
  dir.write("push.jsonl", script);
  const Result v = under_xvfb(dir, "view s.json --mouse push.jsonl --frames 80 --events ev.jsonl --size 800x450");
  INFO(v.err);
  REQUIRE(v.code == 0);
  // The events, as wedge replay --events writes them: the grab of r at the press (frame 2 advances steps
  // 2 and 3), then pulses of r on g, then the release (frame 60: steps 118, 119).
  std::vector<json> events;
  std::istringstream lines(read_file(dir.path() / "ev.jsonl"));
  for (std::string line; std::getline(lines, line);) events.push_back(json::parse(line));
  REQUIRE(events.size() >= 3);
  CHECK(events.front()["type"] == "grab");
  CHECK(events.front()["body"] == "r");
  CHECK(events.front()["step"] == 2);
  CHECK(events.back()["type"] == "release");
  CHECK(events.back()["step"] == 118);
  std::vector<std::int64_t> pulse_steps;
  for (const json& e : events)
    if (e["type"] == "haptic") {
      CHECK(e["bodies"] == json::array({"r", "g"}));
      CHECK(e["hand"] == "right");
      pulse_steps.push_back(e["step"].get<std::int64_t>());
    }
  REQUIRE(!pulse_steps.empty());
  for (std::size_t i = 1; i < pulse_steps.size(); ++i)  // (one per contact begin: the push, then bounces
    CHECK(pulse_steps[i] - pulse_steps[i - 1] >= 6);     // of g off the pushing r, at most one per 50 ms)
  CHECK(events[1]["type"] == "haptic");
  CHECK(events[1]["amplitude"].get<double>() > 0.5);  // the hand was moving at about 1.4 m/s
  // Frame F draws the state after 2 (F - 1) steps. Before the first pulse the held body's hand marker is
  // magenta; just after it the marker and the contact flash yellow for 0.25 s (30 steps, 15 frames); long
  // after the last pulse, still holding: magenta again and no yellow.
  const std::int64_t hit = pulse_steps.front(), last = pulse_steps.back();
  const std::int64_t before = hit / 2 - 1, during = (hit + 1) / 2 + 3, after = (last + 1) / 2 + 20;
  REQUIRE(after < 60);
  auto name = [](std::int64_t f) {  // (built piecewise: GCC 12 warns falsely on "f" + std::string)
    std::string n = "f";
    n += std::to_string(f);
    n += ".png";
    return n;
  };
  for (std::int64_t f : {before, during, after}) {
    std::string args = "view s.json --mouse push.jsonl --frames ";
    args += std::to_string(f);
    args += " --screenshot ";
    args += name(f);
    args += " --size 800x450";
    REQUIRE(under_xvfb(dir, args).code == 0);
  }
  auto shot = [&](std::int64_t f) { return load(dir.path() / name(f)); };
  INFO("pulse steps " << hit << ".." << last << ", frames " << before << ", " << during << ", " << after);
  CHECK(find(shot(before), magenta, kViewLeft).count > 15);
  CHECK(find(shot(before), yellow, kViewLeft).count == 0);
  CHECK(find(shot(during), yellow, kViewLeft).count > 40);  // (both cubes: the hand's grown to 6 cm half size)
  CHECK(find(shot(during), magenta, kViewLeft).count == 0);
  CHECK(find(shot(after), magenta, kViewLeft).count > 15);
  CHECK(find(shot(after), yellow, kViewLeft).count == 0);
}

TEST_CASE("wedge view --contacts marks the contact points where a resting tesseract meets the ground",
          "[cli][view]") {
  TempDir dir;
  dir.write("g.json", R"({"dim": 4, "gravity": [0, -9.81, 0, 0], "bodies": [
    {"name": "ground", "static": true, "shape": {"type": "halfspace", "normal": [0, 1, 0, 0], "offset": 0}},
    {"name": "g", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5, 0.5]}, "position": [0, 0.5, 0, 0], "color": [0, 1, 0]}]})");
  const Result without = under_xvfb(dir, "view g.json --frames 30 --screenshot a.png --size 800x450");
  const Result with = under_xvfb(dir, "view g.json --contacts --frames 30 --screenshot b.png --size 800x450");
  INFO(with.err);
  REQUIRE(without.code == 0);
  REQUIRE(with.code == 0);
  const Image a = load(dir.path() / "a.png"), b = load(dir.path() / "b.png");
  CHECK(find(a, orange, kViewLeft).count == 0);
  const Blob body = find(b, pure(1), kViewLeft), points = find(b, orange, kViewLeft);
  // The face on the ground is a cube in x, z, w; its 8 corners project onto the 4 bottom corners of the
  // slice's cube, drawn over everything: orange, below the body's centre, about as far left as right.
  INFO("body at " << body.x << ", " << body.y << "; contact marks " << points.count << " px at " << points.x << ", "
                  << points.y);
  CHECK(points.count > 20);
  CHECK(points.y > body.y + 20);
  CHECK(std::abs(points.x - body.x) < 30);
  // Four separate marks: orange pixels in each quadrant about their centroid (the far corner, hidden
  // behind the body but drawn over it, is a few pixels across).
  for (int q = 0; q < 4; ++q) {
    const int x0 = q & 1 ? int(points.x) : 316, x1 = q & 1 ? 1 << 20 : int(points.x);
    const int y0 = q & 2 ? int(points.y) : 0, y1 = q & 2 ? 1 << 20 : int(points.y);
    CHECK(find(b, orange, x0, y0, x1, y1).count >= 2);
  }
}

TEST_CASE("wedge view: the body under the cursor is named beside it", "[cli][view]") {
  TempDir dir;
  dir.write("s.json", scene(0.0));
  const Blob green = at_start(dir, 1);
  dir.write("on.jsonl", mouse_line(1, green.x, green.y));
  dir.write("off.jsonl", "{\"frame\":1,\"x\":700,\"y\":420}\n");  // the ground in front of the bodies
  REQUIRE(under_xvfb(dir, "view s.json --mouse on.jsonl --frames 2 --screenshot on.png --size 800x450").code == 0);
  REQUIRE(under_xvfb(dir, "view s.json --mouse off.jsonl --frames 2 --screenshot off.png --size 800x450").code == 0);
  // The label: white text on a dark box just right of and below the cursor.
  auto white = [](const std::uint8_t* p) { return p[0] > 230 && p[1] > 230 && p[2] > 230; };
  auto dark = [](const std::uint8_t* p) { return p[0] < 50 && p[1] < 50 && p[2] < 60; };
  const int gx = int(green.x), gy = int(green.y);
  const Image on = load(dir.path() / "on.png"), off = load(dir.path() / "off.png");
  CHECK(find(on, white, gx + 12, gy + 8, gx + 30, gy + 28).count > 5);
  CHECK(find(on, dark, gx + 8, gy + 6, gx + 30, gy + 28).count > 100);
  CHECK(find(off, dark, 700 + 8, 420 + 6, 700 + 30, 420 + 28).count == 0);
  CHECK(find(off, dark, gx + 8, gy + 6, gx + 30, gy + 28).count == 0);
}

TEST_CASE("wedge view: the w slider moved mid-session, or a body found by name, redraws as the slicer predicts",
          "[cli][view]") {
  TempDir dir;
  dir.write("s.json", scene(0.8));  // blue at w = 0.8, red and green at w = 0 (half size 0.5)
  // Started at w = 0.4, which meets all three (so the camera frames them all): the slider to 0.8 at frame 3,
  // to 0 at frame 8. Started at 0, the panel's list click on "b" at frame 3 (the camera turns to it).
  dir.write("slide.jsonl", "{\"frame\":3,\"x\":0,\"y\":0,\"w\":0.8}\n{\"frame\":8,\"x\":0,\"y\":0,\"w\":[0]}\n");
  const std::string from = "--w 0.4 --mouse slide.jsonl";
  dir.write("find.jsonl", "{\"frame\":3,\"x\":0,\"y\":0,\"find\":\"b\"}\n");
  for (const std::string& run : {from + " --frames 5 --screenshot b.png", from + " --frames 9 --screenshot c.png",
                                 std::string("--mouse find.jsonl --frames 2 --screenshot a.png"),
                                 std::string("--mouse find.jsonl --frames 5 --screenshot d.png")}) {
    const Result r = under_xvfb(dir, "view s.json --size 800x450 " + run);
    INFO(run << ": " << r.err);
    REQUIRE(r.code == 0);
  }
  const std::array<long, 3> a = coverage(dir.path() / "a.png", 316), b = coverage(dir.path() / "b.png", 316),
                            c = coverage(dir.path() / "c.png", 316), d = coverage(dir.path() / "d.png", 316);
  CHECK((a[0] > 500 && a[1] > 500 && a[2] == 0));  // w = 0: |0 - 0.8| > 0.5 hides blue (before the find)
  CHECK((b[0] == 0 && b[1] == 0 && b[2] > 500));   // w = 0.8: only blue
  CHECK((c[0] > 500 && c[1] > 500 && c[2] == 0));  // back at 0
  CHECK((d[0] == 0 && d[1] == 0 && d[2] > 500));   // found: the slice through blue's centre
  // A script asking for what the scene lacks is refused before any window opens, naming file and frame.
  dir.write("bad.jsonl", "{\"frame\":3,\"x\":0,\"y\":0,\"find\":\"nobody\"}\n");
  const Result bad = under_xvfb(dir, "view s.json --mouse bad.jsonl --frames 5 --screenshot e.png");
  CHECK(bad.code == 2);
  CHECK(bad.err.find("bad.jsonl: frame 3: \"find\": s.json has no bounded body named 'nobody'") != std::string::npos);
  CHECK_FALSE(fs::exists(dir.path() / "e.png"));
  dir.write("bad_w.jsonl", "{\"frame\":3,\"x\":0,\"y\":0,\"w\":[0.1,0.2]}\n");
  const Result bad_w = under_xvfb(dir, "view s.json --mouse bad_w.jsonl --frames 5");
  CHECK(bad_w.code == 2);
  CHECK(bad_w.err.find("\"w\" has 2 offsets; a 4D scene has 1") != std::string::npos);
  // A frame that is not a whole number (found by fuzz_mouse_script: 5.5e68 converted to an integer was
  // undefined behaviour) is refused with its line.
  for (const char* frame : {"5.5e68", "1.5", "18446744073709551615"}) {
    INFO(frame);
    dir.write("bad_frame.jsonl", std::string("{\"frame\":1,\"x\":0,\"y\":0}\n{\"frame\":") + frame + ",\"x\":0,\"y\":0}\n");
    const Result bad_frame = under_xvfb(dir, "view s.json --mouse bad_frame.jsonl --frames 5");
    CHECK(bad_frame.code == 2);
    CHECK(bad_frame.err.find("bad_frame.jsonl:2: \"frame\" must be a whole number of frames") != std::string::npos);
  }
}

TEST_CASE("wedge view: the first camera frames what the scene does over its first seconds", "[cli][view]") {
  TempDir dir;
  // A red tesseract thrown straight up at 6 m/s from the ground: its top rises from 1 m to 2.83 m at
  // t = 0.61 s (6^2 / 2g = 1.83 m higher), then it falls back and rests; the green one rests beside it.
  dir.write("up.json", R"({"dim": 4, "gravity": [0, -9.81, 0, 0], "bodies": [
    {"name": "ground", "static": true, "shape": {"type": "halfspace", "normal": [0, 1, 0, 0], "offset": 0}},
    {"name": "r", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5, 0.5]}, "position": [-1, 0.5, 0, 0],
     "velocity": [0, 6, 0, 0], "color": [1, 0, 0]},
    {"name": "g", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5, 0.5]}, "position": [1, 0.5, 0, 0], "color": [0, 1, 0]}]})");
  const Result start = under_xvfb(dir, "view up.json --frames 1 --screenshot f1.png --size 800x450");
  const Result apex = under_xvfb(dir, "view up.json --frames 37 --screenshot f37.png --size 800x450");
  INFO(start.err << apex.err);
  REQUIRE(start.code == 0);
  REQUIRE(apex.code == 0);
  const Blob red1 = blob(dir.path() / "f1.png", 0), red37 = blob(dir.path() / "f37.png", 0);
  const Blob green1 = blob(dir.path() / "f1.png", 1);
  INFO("red at frame 1: rows " << red1.min_y << ".." << red1.max_y << "; at frame 37 (0.6 s): rows " << red37.min_y
                               << ".." << red37.max_y);
  // At its highest the thrown tesseract is still whole in the picture: below the top row by a margin
  // (the fit leaves 5% of the half height), and about as large as at the start (same camera, a little
  // farther away in perspective).
  CHECK(red37.min_y > 5.0);
  CHECK(red37.max_y < red1.min_y);  // it has risen by more than its own height
  CHECK(red37.count > red1.count / 2);
  CHECK(green1.count > 500);
}

TEST_CASE("wedge view: F (or a script's \"fit\") refits the camera to a body that drifted out of the picture",
          "[cli][view]") {
  TempDir dir;
  // No gravity: the red tesseract drifts along x at 2 m/s. The first fit frames its first 3 s (to x = 6 m);
  // by frame 420 (7 s) it is at x = 14 m, out of that picture.
  dir.write("drift.json", R"({"dim": 4, "bodies": [
    {"name": "r", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5, 0.5]}, "position": [0, 0, 0, 0],
     "velocity": [2, 0, 0, 0], "color": [1, 0, 0]},
    {"name": "g", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5, 0.5]}, "position": [0, -2, 0, 0], "color": [0, 1, 0]}]})");
  dir.write("fit.jsonl", mouse_line(400, 0, 0, ",\"fit\":true"));
  const Result lost = under_xvfb(dir, "view drift.json --frames 420 --screenshot lost.png --size 800x450");
  const Result found = under_xvfb(dir, "view drift.json --mouse fit.jsonl --frames 420 --screenshot found.png --size 800x450");
  INFO(lost.err << found.err);
  REQUIRE(lost.code == 0);
  REQUIRE(found.code == 0);
  const Blob red_lost = blob(dir.path() / "lost.png", 0), red_found = blob(dir.path() / "found.png", 0);
  const Blob green_found = blob(dir.path() / "found.png", 1);
  CHECK(red_lost.count == 0);     // drifted out of the first fit
  CHECK(red_found.count > 100);   // refitted at frame 400: in the picture again
  CHECK(green_found.count > 100); // and the green one with it
}

// `wedge xr` as a user runs it without a headset: headless, through the real OpenXR loader (Debian's
// libopenxr-loader1), on Wedge's replay runtime (xr/runtime) playing a shipped recording as an Oculus
// Touch pair. What it is held to is `wedge replay` of the same file, which reads the recording directly
// and shares no OpenXR code: the same grabs and releases at the same steps, the haptic calls the runtime
// logged are replay's pulses (hands and order; amplitudes within 1e-3, the runtime logging the float that
// OpenXR carries), and the bodies where replay leaves them within 1e-6 m for as long as the hands drive
// them. The two paths sample differently in two places only: XrTime is integer nanoseconds (a step at
// k h is located at X0 + round(k h 1e9)), and XrPosef is 32-bit float (6e-8 m at 1 m). A session's own
// --record, replayed, ends in exactly the hash it printed. Failures (no runtime, a refused system or
// session, an unreadable recording) are one clear line and exit 2 within seconds; Ctrl-C ends the session
// with its files whole; Khronos's core validation layer reports nothing.
#ifdef WEDGE_XR_MANIFEST
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "cli_runner.hpp"
#include "png_pixels.hpp"
#include "wedge/recordings/recording.hpp"

using namespace cli_runner;

namespace {

const fs::path kRoot = WEDGE_SOURCE_DIR;

std::vector<json> read_lines(const fs::path& p) {
  std::vector<json> v;
  std::istringstream in(read_file(p));
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) v.push_back(json::parse(line));
  return v;
}

double distance(const json& a, const json& b) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += std::pow(a[i].get<double>() - b[i].get<double>(), 2);
  return std::sqrt(s);
}

// The environment that puts the replay runtime behind the loader, playing `recording`.
std::string runtime_env(const std::string& recording) {
  return "XR_RUNTIME_JSON=" WEDGE_XR_MANIFEST " WEDGE_XR_REPLAY=" + (kRoot / recording).string() +
         " WEDGE_XR_HAPTICS_LOG=haptics.jsonl";
}

struct Run {
  Result result;
  std::vector<json> states, events, haptics;
  std::string hash;  // printed on stdout
};

Run run_xr(const TempDir& dir, const std::string& scene, const std::string& recording, const std::string& extra = "") {
  Run r;
  r.result = dir.shell(runtime_env(recording) + " $WEDGE xr " + (kRoot / scene).string() +
                       " --headless --hash --out xr_states.jsonl --events xr_events.jsonl --record xr_session.jsonl " +
                       extra);
  if (r.result.code != 0) return r;
  r.states = read_lines(dir.path() / "xr_states.jsonl");
  r.events = read_lines(dir.path() / "xr_events.jsonl");
  r.haptics = read_lines(dir.path() / "haptics.jsonl");
  const std::size_t at = r.result.out.find("state hash ");
  if (at != std::string::npos) r.hash = r.result.out.substr(at + 11, 16);
  return r;
}

struct Case {
  const char* scene;
  const char* recording;
  bool driven_throughout;  // no impact amplifies the float poses' rounding (see below)
};

}  // namespace

TEST_CASE("wedge xr: headless over the replay runtime does what wedge replay does, and its recording replays to its hash",
          "[cli][xr]") {
  const Case cases[] = {{"scenes/toy_table_4d.json", "recordings/scripted/toy_table_grab.jsonl", false},
                        {"scenes/fig3_dominoes_4d.json", "recordings/scripted/dominoes_push.jsonl", false},
                        {"scenes/toy_table_4d.json", "recordings/quest2/sample_movement.jsonl", true}};
  for (const Case& c : cases) {
    INFO(c.recording);
    TempDir dir;
    const Run xr = run_xr(dir, c.scene, c.recording);
    INFO(xr.result.err);
    REQUIRE(xr.result.code == 0);
    CHECK(xr.result.out.find("xr session on 'Wedge replay runtime' (headless)") != std::string::npos);
    CHECK(xr.result.out.find("ended: the runtime ended the session") != std::string::npos);  // the recording ran out
    REQUIRE(xr.hash.size() == 16);
    CHECK(xr.states.back()["state_hash"] == xr.hash);
    const double end = xr.states[xr.states.size() - 2]["time"].get<double>();

    // The same recording through `wedge replay`, to the same time.
    const Result rp = dir.run("replay " + (kRoot / c.scene).string() + " " + (kRoot / c.recording).string() +
                              " --out replay_states.jsonl --events replay_events.jsonl --until " + std::to_string(end));
    REQUIRE(rp.code == 0);
    const std::vector<json> states = read_lines(dir.path() / "replay_states.jsonl");
    const std::vector<json> events = read_lines(dir.path() / "replay_events.jsonl");

    // Grabs and releases: the same, at the same steps.
    std::vector<json> grabs_xr, grabs_rp, pulses;
    for (const json& e : xr.events)
      if (e["type"] != "haptic") grabs_xr.push_back(e);
    for (const json& e : events) (e["type"] == "haptic" ? pulses : grabs_rp).push_back(e);
    REQUIRE(grabs_xr.size() == grabs_rp.size());
    CHECK(grabs_rp.size() >= 2);  // every shipped session grabs and lets go
    for (std::size_t i = 0; i < grabs_rp.size(); ++i) {
      CHECK(grabs_xr[i]["type"] == grabs_rp[i]["type"]);
      CHECK(grabs_xr[i]["step"] == grabs_rp[i]["step"]);
      CHECK(grabs_xr[i]["body"] == grabs_rp[i]["body"]);
    }
    // Haptics: the runtime's log of xrApplyHapticFeedback is replay's pulse list. Each call was made in
    // the frame whose display time first covered the pulse's step: within one 90 Hz frame after it.
    std::vector<json> applied;
    for (const json& h : xr.haptics)
      if (h["call"] == "apply") applied.push_back(h);
    REQUIRE(applied.size() == pulses.size());
    for (std::size_t i = 0; i < pulses.size(); ++i) {
      CHECK(applied[i]["hand"] == "/user/hand/" + pulses[i]["hand"].get<std::string>());
      CHECK(applied[i]["amplitude"].get<double>() == Approx(pulses[i]["amplitude"].get<double>()).margin(1e-3));
      CHECK(applied[i]["duration_ns"].get<std::int64_t>() == 30'000'000);
      const double t = applied[i]["t"].get<double>(), step_t = pulses[i]["t"].get<double>();
      CHECK(t >= step_t - 1e-9);
      CHECK(t < step_t + 1.0 / 90.0 + 1.0 / 120.0);
    }

    // The bodies: within 1e-6 m of replay's while the hands drive them (float poses round to 6e-8 m at
    // 1 m). A hard impact or a throw amplifies that rounding as any 1e-8 m change would (a tumbling body
    // is chaotic), so the scripted sessions are compared up to their first haptic pulse, the Quest stream
    // (no impact) throughout.
    std::int64_t limit = states.back()["step"].get<std::int64_t>();
    if (!c.driven_throughout && !pulses.empty()) limit = pulses.front()["step"].get<std::int64_t>();
    double worst = 0.0;
    std::size_t compared = 0;
    for (std::size_t i = 0; i < std::min(states.size(), xr.states.size() - 1); ++i) {
      REQUIRE(states[i]["step"] == xr.states[i]["step"]);
      if (states[i]["step"].get<std::int64_t>() > limit) break;
      for (std::size_t b = 0; b < states[i]["bodies"].size(); ++b)
        worst = std::max(worst, distance(states[i]["bodies"][b]["center"], xr.states[i]["bodies"][b]["center"]));
      ++compared;
    }
    INFO("compared " << compared << " states to step " << limit << ": max |x_xr - x_replay| = " << worst << " m");
    CHECK(compared > 200);
    CHECK(worst < 1e-6);

    // The session's own recording: one sample per step of each tracked hand; replayed, the printed hash.
    const wedge::recordings::Recording rec = wedge::recordings::read_recording((dir.path() / "xr_session.jsonl").string());
    CHECK(rec.source == "xr");
    CHECK(rec.warnings.empty());
    CHECK(rec.hands.size() >= states.size() - 2);
    const Result again = dir.run("replay " + (kRoot / c.scene).string() + " xr_session.jsonl --every 1000000 --hash --until " +
                                 std::to_string(end));
    REQUIRE(again.code == 0);
    CHECK(again.lines().back()["state_hash"] == xr.hash);
  }
}

TEST_CASE("wedge xr: no runtime, a refused system or session, an unreadable recording: one line, exit 2, no output",
          "[cli][xr]") {
  TempDir dir;
  const std::string scene = (kRoot / "scenes/toy_table_4d.json").string();
  struct Failure {
    std::string env, expect;
  };
  const Failure failures[] = {
      {"XR_RUNTIME_JSON=/nonexistent/runtime.json", "no OpenXR runtime (XR_ERROR_RUNTIME_UNAVAILABLE): "
                                                    "XR_RUNTIME_JSON=/nonexistent/runtime.json names no loadable"},
      {"XR_RUNTIME_JSON= HOME=/nonexistent XDG_CONFIG_HOME= XDG_CONFIG_DIRS=/nonexistent",
       "XR_RUNTIME_JSON is not set and there is no active runtime (looked for /nonexistent/.config/openxr/1/"
       "active_runtime.json, /nonexistent/openxr/1/active_runtime.json, /etc/openxr/1/active_runtime.json)"},
      {runtime_env("recordings/scripted/toy_table_grab.jsonl") + " WEDGE_XR_REFUSE=system", "has no headset connected"},
      {runtime_env("recordings/scripted/toy_table_grab.jsonl") + " WEDGE_XR_REFUSE=session",
       "xrCreateSession: XR_ERROR_RUNTIME_FAILURE"},
      {runtime_env("recordings/no_such_recording.jsonl"), "xrCreateInstance: XR_ERROR_RUNTIME_FAILURE"},
  };
  for (const Failure& f : failures) {
    INFO(f.env);
    const auto t0 = std::chrono::steady_clock::now();
    const Result r = dir.shell("env " + f.env + " timeout 20 $WEDGE xr " + scene +
                               " --headless --out states.jsonl --record session.jsonl");
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    INFO(r.err);
    CHECK(r.code == 2);
    CHECK(seconds < 10.0);
    CHECK(r.err.find("wedge: " + scene + ": ") != std::string::npos);
    CHECK(r.err.find(f.expect) != std::string::npos);
    CHECK(!fs::exists(dir.path() / "states.jsonl"));
  }
  // The unreadable recording is named by the runtime (its own line), and the app's line follows.
  const Result r = dir.shell(runtime_env("recordings/no_such_recording.jsonl") + " $WEDGE xr " + scene + " --headless");
  CHECK(r.err.find("no_such_recording.jsonl") != std::string::npos);
}

TEST_CASE("wedge xr: Ctrl-C ends the session cleanly, every file whole", "[cli][xr]") {
  TempDir dir;
  // With no recording to play the runtime never ends the session: only the signal does.
  const Result r = dir.shell("XR_RUNTIME_JSON=" WEDGE_XR_MANIFEST " $WEDGE xr " + (kRoot / "scenes/toy_table_4d.json").string() +
                             " --headless --hash --every 1000 --out states.jsonl --record session.jsonl & "
                             "sleep 1; kill -INT $!; wait $!");
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(r.err.find("interrupted (SIGINT): ending the session") != std::string::npos);
  CHECK(r.out.find("ended: exit requested") != std::string::npos);
  const std::vector<json> states = read_lines(dir.path() / "states.jsonl");
  REQUIRE(states.size() >= 2);
  CHECK(states.back().contains("state_hash"));
  const wedge::recordings::Recording rec = wedge::recordings::read_recording((dir.path() / "session.jsonl").string());
  CHECK(rec.warnings.empty());  // no torn line
  CHECK(!rec.heads.empty());
}

// Nothing lost on a crash: --record writes each line whole and flushed as the session goes, so a session
// killed outright (SIGKILL: no handler runs, nothing is closed) leaves a file whose lines are exactly the
// first lines of the uninterrupted session's recording (the runtime plays the same stream on the same
// clock), at most one torn line after them, and whose complete lines replay: `wedge replay` warns about
// the torn line and reads every other one.
TEST_CASE("wedge xr --record: a session killed with SIGKILL leaves every complete line, and they replay", "[cli][xr]") {
  TempDir dir;
  const std::string scene = (kRoot / "scenes/toy_table_4d.json").string();
  const std::string xr = runtime_env("recordings/quest2/sample_movement.jsonl") + " $WEDGE xr " + scene + " --headless";
  const Result full = dir.shell(xr + " --record full.jsonl");
  REQUIRE(full.code == 0);
  // Killed once the recording holds 3000 lines (about a quarter of the session), polled every 10 ms.
  const Result killed = dir.shell(xr + " --record killed.jsonl & n=0; "
                                  "while [ $(cat killed.jsonl 2>/dev/null | wc -l) -lt 3000 ] && [ $n -lt 6000 ]; do "
                                  "sleep 0.01; n=$((n+1)); done; kill -KILL $!; wait $!");
  CHECK(killed.code == 128 + 9);
  const std::string whole = read_file(dir.path() / "full.jsonl"), cut = read_file(dir.path() / "killed.jsonl");
  const std::size_t complete = cut.rfind('\n') + 1;  // the complete lines' bytes
  REQUIRE(std::count(cut.begin(), cut.end(), '\n') >= 3000);
  REQUIRE(cut.size() < whole.size());  // killed before the end
  CHECK(whole.compare(0, cut.size(), cut) == 0);  // every byte written, torn tail included, is the full run's
  const Result replayed = dir.run("replay " + scene + " killed.jsonl --hash");
  INFO(replayed.err);
  CHECK(replayed.code == 0);
  CHECK((complete == cut.size()) == (replayed.err.find("torn last line") == std::string::npos));
  const wedge::recordings::Recording rec = wedge::recordings::read_recording((dir.path() / "killed.jsonl").string());
  const auto lines = std::count(cut.begin(), cut.begin() + std::ptrdiff_t(complete), '\n');
  CHECK(std::ptrdiff_t(1 + rec.hands.size() + rec.heads.size() + rec.motion.size()) == lines);  // header + samples
}

TEST_CASE("wedge xr: Khronos's core validation layer, loaded, reports nothing", "[cli][xr]") {
  TempDir dir;
  const Result r = dir.shell(runtime_env("recordings/scripted/toy_table_grab.jsonl") +
                             " XR_ENABLE_API_LAYERS=XR_APILAYER_LUNARG_core_validation XR_CORE_VALIDATION_EXPORT_TYPE=text"
                             " XR_CORE_VALIDATION_FILE_NAME=validation.txt XR_LOADER_DEBUG=info $WEDGE xr " +
                             (kRoot / "scenes/toy_table_4d.json").string() + " --headless");
  INFO(r.out + r.err);
  REQUIRE(r.code == 0);
  CHECK((r.out + r.err).find("succeeded loading layer XR_APILAYER_LUNARG_core_validation") != std::string::npos);
  const std::string report = fs::exists(dir.path() / "validation.txt") ? read_file(dir.path() / "validation.txt") : "";
  CHECK(report == "");
}

namespace {

Eigen::Vector3d vec3(const json& a) { return {a[0].get<double>(), a[1].get<double>(), a[2].get<double>()}; }
Eigen::Quaterniond quat_xyzw(const json& a) {
  return Eigen::Quaterniond(a[3].get<double>(), a[0].get<double>(), a[1].get<double>(), a[2].get<double>());
}

// Where a tracking-space point falls in an eye's image (px from the top left), from the view the app
// submitted (the runtime's sidecar): the pinhole of the eye's pose and its four fov angles, written here
// from the OpenXR definitions, independent of the renderer's matrices.
Eigen::Vector2d project(const json& frame, const json& eye, const Eigen::Vector3d& point) {
  const Eigen::Quaterniond space_q = quat_xyzw(frame["space"]["pose"]["orientation"]);
  const Eigen::Vector3d space_p = vec3(frame["space"]["pose"]["position"]);
  const Eigen::Quaterniond q = space_q * quat_xyzw(eye["pose"]["orientation"]);
  const Eigen::Vector3d e = space_p + space_q * vec3(eye["pose"]["position"]);
  const Eigen::Vector3d c = q.conjugate() * (point - e);  // camera frame: x right, y up, looking down -z
  const double tx = c.x() / -c.z(), ty = c.y() / -c.z();
  const json& fov = eye["fov"];
  const double l = std::tan(fov["angle_left"].get<double>()), r = std::tan(fov["angle_right"].get<double>());
  const double d = std::tan(fov["angle_down"].get<double>()), u = std::tan(fov["angle_up"].get<double>());
  const double w = eye["image_rect"]["width"].get<double>(), h = eye["image_rect"]["height"].get<double>();
  return {(tx - l) / (r - l) * w, (u - ty) / (u - d) * h};
}

}  // namespace

TEST_CASE("wedge xr: each eye shows the held tesseract where its view projects it, the two apart by the parallax",
          "[cli][xr]") {
  // A red tesseract on the floor in front of a person at a table; the right hand takes it at 0.2 s and
  // lifts it to chest height, where it is held from 1.2 s on. The runtime writes what the app submitted:
  // both eyes' images and each eye's pose and field of view.
  TempDir dir;
  dir.write("scene.json", R"({"dim": 4, "timestep": 0.008333333333333333,
    "interaction": {"origin": [0, 1.6, 0, 0]},
    "bodies": [
      {"name": "floor", "static": true, "shape": {"type": "halfspace", "normal": [0, 1, 0, 0], "offset": 0}},
      {"name": "red", "shape": {"type": "box", "half_extents": [0.08, 0.08, 0.08, 0.08]}, "position": [0, 0.08, -0.45, 0],
       "color": [1, 0, 0]}]})");
  std::string rec = R"({"format":"wedge-recording","version":1,"source":"script","units":{"time":"s","position":"m","acceleration":"g","rotation_rate":"rad/s"},"conventions":{}})";
  rec += "\n";
  for (int i = 0; i <= 200; ++i) {  // 100 Hz, 2 s
    const double t = i * 0.01, lift = std::clamp((t - 0.3) / 0.9, 0.0, 1.0);
    const double y = -1.52 + 0.9 * lift, z = -0.45 + 0.1 * lift;  // tracking: the floor is at y = -1.6
    rec += R"({"t":)" + std::to_string(t) + R"(,"type":"hand","hand":"right","position":[0,)" + std::to_string(y) + "," +
           std::to_string(z) + R"(],"orientation":[1,0,0,0],"squeeze":)" + (t >= 0.2 ? "1" : "0") +
           R"(,"trigger":0,"buttons":[],"mode4d":false})" + "\n";
  }
  dir.write("lift.jsonl", rec);
  fs::create_directory(dir.path() / "frames");
  const Result r = dir.shell(
      "rm -f display; Xvfb -displayfd 5 -screen 0 1280x1024x24 -nolisten tcp 5>display 2>/dev/null & x=$!; "
      "i=0; while [ ! -s display ] && [ $i -lt 100 ]; do sleep 0.05; i=$((i+1)); done; "
      "DISPLAY=:$(cat display) XR_RUNTIME_JSON=" WEDGE_XR_MANIFEST " WEDGE_XR_REPLAY=lift.jsonl WEDGE_XR_FRAMES=frames "
      "WEDGE_XR_FRAMES_EVERY=45 \"$WEDGE\" xr scene.json --out states.jsonl --events events.jsonl; rc=$?; kill $x; exit $rc");
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("(rendered)") != std::string::npos);
  const std::vector<json> states = read_lines(dir.path() / "states.jsonl");
  const std::vector<json> events = read_lines(dir.path() / "events.jsonl");
  REQUIRE(!events.empty());
  CHECK(events[0]["type"] == "grab");
  CHECK(events[0]["body"] == "red");

  // Frames 135 and 180 (1.5 s and 2.0 s): held still at chest height. The body's centre at that frame is
  // the state after the steps whose times are at or before the frame's (the app draws after stepping).
  int checked = 0;
  for (int f : {135, 180}) {
    char name[64];
    std::snprintf(name, sizeof name, "frame_%06d.json", f);
    INFO(name);
    REQUIRE(fs::exists(dir.path() / "frames" / name));
    const json frame = json::parse(read_file(dir.path() / "frames" / name));
    const double t = frame["t"].get<double>();
    const std::int64_t steps = std::int64_t(std::floor(t * 120.0 + 1e-6)) + 1;
    const json* state = nullptr;
    for (const json& s : states)
      if (s["step"] == steps) state = &s;
    REQUIRE(state != nullptr);
    REQUIRE((*state)["hands"][1]["holding"] == "red");
    const json& body = (*state)["bodies"][1];
    const Eigen::Vector3d centre(body["center"][0].get<double>(), body["center"][1].get<double>() - 1.6,
                                 body["center"][2].get<double>());  // world -> tracking (origin (0, 1.6, 0))
    std::array<Eigen::Vector2d, 2> expected, seen;
    for (int e = 0; e < 2; ++e) {
      const json& eye = frame["eyes"][std::size_t(e)];
      expected[std::size_t(e)] = project(frame, eye, centre);
      const Blob b = find(load(dir.path() / "frames" / eye["image"].get<std::string>()), pure(0));
      INFO("eye " << e << ": the centre projects to (" << expected[std::size_t(e)].transpose() << "), the red pixels' "
                  << b.count << " centroid (" << b.x << ", " << b.y << ")");
      REQUIRE(b.count > 500);  // (a 16 cm cube 0.6 m away: thousands of pixels)
      seen[std::size_t(e)] = {b.x, b.y};
      // The cube's visible faces are not quite symmetric about its centre's projection (seen here within
      // 1.5 px): the tolerance is 4 px, a tenth of its apparent size; and the projection lies in the blob.
      CHECK((seen[std::size_t(e)] - expected[std::size_t(e)]).norm() < 4.0);
      CHECK(expected[std::size_t(e)].x() > b.min_x);
      CHECK(expected[std::size_t(e)].x() < b.max_x);
      CHECK(expected[std::size_t(e)].y() > b.min_y);
      CHECK(expected[std::size_t(e)].y() < b.max_y);
    }
    // Parallax: the left eye sees the cube further right than the right eye does, by the disparity the
    // 63 mm between the eyes gives at its depth (the faces' asymmetry cancels between eyes to ~1 px).
    const double disparity = expected[0].x() - expected[1].x(), measured = seen[0].x() - seen[1].x();
    INFO("disparity: expected " << disparity << " px, measured " << measured << " px");
    CHECK(disparity > 10.0);
    CHECK(measured == Approx(disparity).margin(2.0));
    ++checked;
  }
  CHECK(checked == 2);
}

TEST_CASE("wedge xr: a runtime that predicts display time 0 (as Monado headless does) is paced on its clock",
          "[cli][xr]") {
  // No time <= 0 is passed on: the app takes the runtime's clock (XR_KHR_convert_timespec_time) and sleeps
  // to the display period, so the 7.5 s session takes about 7.5 s of wall time and still grabs, hits and
  // lets go. (Buttons then come from the runtime's frame count and poses from its clock, which drift
  // apart by the sleeps' overshoot: this checks survival, not replay fidelity.)
  TempDir dir;
  const auto t0 = std::chrono::steady_clock::now();
  const Result r = dir.shell(runtime_env("recordings/scripted/toy_table_grab.jsonl") +
                             " WEDGE_XR_QUIRKS=zero-display-time timeout 60 $WEDGE xr " +
                             (kRoot / "scenes/toy_table_4d.json").string() + " --headless --events events.jsonl");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.find("predictedDisplayTime 0): pacing on the runtime's clock") != std::string::npos);
  CHECK(seconds > 6.5);
  CHECK(seconds < 30.0);
  int grabs = 0, releases = 0, pulses = 0;
  for (const json& e : read_lines(dir.path() / "events.jsonl")) {
    grabs += e["type"] == "grab";
    releases += e["type"] == "release";
    pulses += e["type"] == "haptic";
  }
  CHECK(grabs == 1);
  CHECK(releases == 1);
  CHECK(pulses >= 1);
  CHECK(read_lines(dir.path() / "haptics.jsonl").size() == std::size_t(pulses));
}

TEST_CASE("wedge xr: a hand that loses tracking lets go after 0.1 s, and a refused binding costs only itself",
          "[cli][xr]") {
  // The runtime loses the right controller from 1.0 s to 1.5 s (no samples; WEDGE_XR_QUIRKS=lose-tracking)
  // while it holds a tesseract 0.5 m up, and refuses one Touch binding (the left X button). The app must
  // keep the rest of the Touch profile (the grab works), hold the lost hand's pose for 0.1 s and then let
  // go: the tesseract falls to the floor under gravity. The session's recording says so, sample by sample:
  // replayed, it ends in the printed hash.
  TempDir dir;
  dir.write("scene.json", R"({"dim": 4, "timestep": 0.008333333333333333, "gravity": [0, -9.81, 0, 0],
    "interaction": {"origin": [0, 1.6, 0, 0]},
    "bodies": [
      {"name": "floor", "static": true, "shape": {"type": "halfspace", "normal": [0, 1, 0, 0], "offset": 0}},
      {"name": "red", "shape": {"type": "box", "half_extents": [0.08, 0.08, 0.08, 0.08]}, "position": [0, 0.08, -0.45, 0]}]})");
  std::string rec = R"({"format":"wedge-recording","version":1,"source":"script","units":{"time":"s","position":"m","acceleration":"g","rotation_rate":"rad/s"},"conventions":{}})";
  rec += "\n";
  for (int i = 0; i <= 250; ++i) {  // 100 Hz for 2.5 s, none in (1.0, 1.5)
    if (i > 100 && i < 150) continue;
    const double t = i * 0.01, y = -1.52 + 0.5 * std::clamp((t - 0.3) / 0.5, 0.0, 1.0);
    rec += R"({"t":)" + std::to_string(t) + R"(,"type":"hand","hand":"right","position":[0,)" + std::to_string(y) +
           R"(,-0.45],"orientation":[1,0,0,0],"squeeze":)" + (t >= 0.2 && t < 1.8 ? "1" : "0") +
           R"(,"trigger":0,"buttons":[],"mode4d":false})" + "\n";
  }
  dir.write("gap.jsonl", rec);
  const Result r = dir.shell("XR_RUNTIME_JSON=" WEDGE_XR_MANIFEST " WEDGE_XR_REPLAY=gap.jsonl "
                             "WEDGE_XR_QUIRKS=lose-tracking,refuse-binding=/user/hand/left/input/x/click $WEDGE xr "
                             "scene.json --headless --hash --out states.jsonl --events events.jsonl --record session.jsonl");
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.find("binding /user/hand/left/input/x/click refused (XR_ERROR_PATH_UNSUPPORTED); the profile's other "
                   "bindings kept") != std::string::npos);
  CHECK(r.err.find("/user/hand/right: /interaction_profiles/oculus/touch_controller") != std::string::npos);
  std::vector<json> events;
  for (const json& e : read_lines(dir.path() / "events.jsonl"))
    if (e["type"] != "haptic") events.push_back(e);
  REQUIRE(events.size() >= 2);
  CHECK(events[0]["type"] == "grab");
  CHECK(events[0]["t"].get<double>() == Approx(0.2).margin(1.0 / 120));
  CHECK(events[1]["type"] == "release");
  // Lost after the sample at 1.0 s; let go at the first step more than 0.1 s later.
  CHECK(events[1]["t"].get<double>() > 1.1);
  CHECK(events[1]["t"].get<double>() <= 1.1 + 1.0 / 120 + 1e-9);
  const std::vector<json> states = read_lines(dir.path() / "states.jsonl");
  auto height_at = [&](double t) {
    for (const json& s : states)
      if (s.contains("time") && s["time"].get<double>() >= t - 1e-9) return s["bodies"][1]["center"][1].get<double>();
    return -1.0;
  };
  CHECK(height_at(1.0) == Approx(0.58).margin(0.01));  // held 0.5 m up
  CHECK(height_at(1.45) == Approx(0.08).margin(0.005));  // dropped (0.5 m takes 0.32 s) and at rest on the floor
  const std::size_t at = r.out.find("state hash ");
  REQUIRE(at != std::string::npos);
  const Result again = dir.run("replay scene.json session.jsonl --every 1000000 --hash --until " +
                               std::to_string(states[states.size() - 2]["time"].get<double>()));
  REQUIRE(again.code == 0);
  CHECK(again.lines().back()["state_hash"] == r.out.substr(at + 11, 16));
}

#endif  // WEDGE_XR_MANIFEST
